#!/usr/bin/env bash
# Installs the build into a scratch prefix, then builds and runs tests/install/consumer.c against
# it twice: with pkg-config and with find_package(indentmap). Fails when a header, the library,
# the .pc file or the CMake package is missing or wrong.
#   install.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 source=$2
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix" >/dev/null
lib=$(find "$prefix" -name 'libindentmap.so' -printf '%h\n' | head -1)
[ -n "$lib" ] || { echo "install: no libindentmap.so under $prefix" >&2; exit 1; }
soname=$(objdump -p "$lib/libindentmap.so" | awk '/SONAME/ {print $2}')
case "$soname" in libindentmap.so.[0-9]*) ;; *) echo "install: SONAME '$soname'" >&2; exit 1 ;; esac
[ -f "$lib/libindentmap.a" ] || { echo "install: no static library" >&2; exit 1; }

export PKG_CONFIG_PATH="$lib/pkgconfig"
# shellcheck disable=SC2046
cc -std=c11 -Wall -Wextra -Werror -o "$prefix/consumer_pc" "$source/consumer.c" \
   $(pkg-config --cflags --libs indentmap) -lm -Wl,-rpath,"$lib"
"$prefix/consumer_pc"

cmake -S "$source" -B "$prefix/consumer_build" -DCMAKE_PREFIX_PATH="$prefix" \
      -DCMAKE_BUILD_RPATH="$lib" >/dev/null
cmake --build "$prefix/consumer_build" >/dev/null
"$prefix/consumer_build/consumer"
# The program must have been linked with the shared library, not with a copy of it.
ldd "$prefix/consumer_build/consumer" | grep -q "libindentmap.so.$(echo "$soname" | sed 's/.*\.so\.//')"
echo "install: pkg-config and find_package consumers ran against $soname"
