#!/usr/bin/env bash
# The C sources keep the style of .clang-format (applied to every file once, issue 28): clang-format
# would change nothing. A file it would change fails the test, with the first of its changes; run
# `clang-format-14 -i FILE` on the files named.
#   style.sh CLANG_FORMAT SOURCE_DIR
set -u
clang_format=$1
cd "$2" || exit 1
files=$(find src include tests bench fuzz python/src examples -name '*.[ch]' | sort)
[ -n "$files" ] || { echo "style: no C files found under $2"; exit 1; }
bad=0
for f in $files; do
  if ! "$clang_format" --style=file --dry-run --Werror "$f" > /dev/null 2>&1; then
    echo "style: $f is not as .clang-format has it; the first change:"
    "$clang_format" --style=file "$f" | diff "$f" - | head -6
    bad=$((bad + 1))
  fi
done
[ "$bad" -eq 0 ] || { echo "style: $bad of $(echo "$files" | wc -l) files differ"; exit 1; }
echo "style: $(echo "$files" | wc -l) files as .clang-format has them"
