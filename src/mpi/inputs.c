/* Every rank of an MPI run started alike (agree.h: mpi_same_inputs). Ranks that solve one grid or
 * share one scene from different arguments would wait in collectives that never match, or write
 * outside the folder rank 0 locked: a hash of what each rank was given, gathered at the start,
 * stops them all with one message instead. */
#include "mpi/agree.h"
#include "core/fnv1a.h"
#include "indentmap/status.h"
#include "io/checksum.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* What a rank was given: the hash and length of its words (working folder, then the arguments,
 * each ended by '\0'), and the hash of the file's bytes. */
enum { WORDS_HASH, WORDS_LENGTH, FILE_HASH, RECORD };

/* The working folder and the arguments, each ended by '\0', in *words (caller frees). */
static int words_of(int count, char **args, char **words, size_t *length)
{
    char folder[4096];
    if (!getcwd(folder, sizeof folder))
        return im_fail(IM_EIO, "cannot read the working folder: %s", strerror(errno));
    *length = strlen(folder) + 1;
    for (int i = 0; i < count; ++i)
        *length += strlen(args[i]) + 1;
    char *at = *words = malloc(*length);
    if (!at)
        return im_fail(IM_ENOMEM, "the arguments of the command (%zu bytes)", *length);
    at = stpcpy(at, folder) + 1;
    for (int i = 0; i < count; ++i)
        at = stpcpy(at, args[i]) + 1;
    return IM_OK;
}

/* FNV-1a of the file's bytes. */
static int file_hash(const char *path, uint64_t *hash)
{
    FILE *stream = fopen(path, "rb");
    if (!stream)
        return im_fail(IM_EIO, "%s: cannot open: %s", path, strerror(errno));
    char *bytes = NULL;
    size_t length = 0, size = 0;
    int status = IM_OK;
    while (status == IM_OK && !feof(stream)) {
        char *grown = length == size ? realloc(bytes, size = 2 * size + 65536) : bytes;
        if (!grown)
            status = im_fail(IM_ENOMEM, "%s: reading %zu bytes", path, size);
        else
            length += fread((bytes = grown) + length, 1, size - length, stream);
        if (status == IM_OK && ferror(stream))
            status = im_fail(IM_EIO, "%s: cannot read: %s", path, strerror(errno));
    }
    fclose(stream);
    if (status == IM_OK)
        *hash = fnv1a_add(FNV1A_START, bytes, length);
    free(bytes);
    return status;
}

/* "rank 1's argument 5 is 'o2' (after --out), rank 0's 'o1'": the first word in which theirs
 * differs from mine (word 0 the working folder). */
static void describe(const char *mine, size_t mine_length, const char *theirs, size_t theirs_length, int rank,
                     char *text, size_t size)
{
    const char *mine_end = mine + mine_length, *theirs_end = theirs + theirs_length, *before = NULL;
    int word = 0;
    for (; mine < mine_end && theirs < theirs_end && strcmp(mine, theirs) == 0; ++word) {
        before = mine;
        mine += strlen(mine) + 1;
        theirs += strlen(theirs) + 1;
    }
    if (word == 0)
        snprintf(text, size, "rank %d runs in the folder %s, rank 0 in %s", rank, theirs, mine);
    else if (mine == mine_end)
        snprintf(text, size, "rank %d has an argument %d, '%s', which rank 0 has not", rank, word, theirs);
    else if (theirs == theirs_end)
        snprintf(text, size, "rank %d lacks rank 0's argument %d, '%s'", rank, word, mine);
    else if (word > 1 && strncmp(before, "--", 2) == 0)
        snprintf(text, size, "rank %d's argument %d is '%s' (after %s), rank 0's '%s'", rank, word, theirs, before,
                 mine);
    else
        snprintf(text, size, "rank %d's argument %d is '%s', rank 0's '%s'", rank, word, theirs, mine);
}

/* Adds the count-th differing rank to list, "1, 3" (the first eight, then "..."). */
static void list_rank(char *list, size_t size, int count, int rank)
{
    size_t used = strlen(list);
    if (count <= 8 && used < size)
        snprintf(list + used, size - used, "%s%d", count > 1 ? ", " : "", rank);
    else if (count == 9 && used < size)
        snprintf(list + used, size - used, ", ...");
}

/* "1, 3" (the first few): the ranks whose record differs from rank 0's in field (the words: in
 * hash or length); their count, and the first of them in *first. */
static int differing_ranks(const uint64_t *records, int ranks, int field, char *list, size_t size, int *first)
{
    int count = 0;
    list[0] = '\0';
    for (int r = 1; r < ranks; ++r) {
        if (records[(size_t)r * RECORD + field] == records[field] &&
            (field != WORDS_HASH || records[(size_t)r * RECORD + WORDS_LENGTH] == records[WORDS_LENGTH]))
            continue;
        if (count == 0)
            *first = r;
        list_rank(list, size, ++count, r);
    }
    return count;
}

/* The message for ranks that read other bytes than rank 0 from file (key: the scene key naming it,
 * or NULL). */
static int other_bytes(const char *file, const char *key, const char *list, int count)
{
    return im_fail(IM_EINVAL,
                   "%s%s%s%s: rank%s %s read%s other bytes from it than rank 0: every rank must read the "
                   "same file",
                   file, key ? " (" : "", key ? key : "", key ? ")" : "", count > 1 ? "s" : "", list,
                   count > 1 ? "" : "s");
}

/* Rank 0's message for words that differ: the ranks' words gathered on rank 0. */
static int words_differ(MPI_Comm comm, const uint64_t *records, int ranks, const char *words, const char *list,
                        int count, int first)
{
    int rank, *lengths = malloc(sizeof(int) * 2 * (size_t)ranks);
    MPI_Comm_rank(comm, &rank);
    size_t total = 0;
    for (int r = 0; lengths && r < ranks; ++r) {
        lengths[r] = (int)records[(size_t)r * RECORD + WORDS_LENGTH];
        lengths[ranks + r] = (int)total;
        total += (size_t)lengths[r];
    }
    char *all = rank == 0 ? malloc(total + 1) : NULL;
    int gathered = lengths && (rank != 0 || all), everywhere;
    MPI_Allreduce(&gathered, &everywhere, 1, MPI_INT, MPI_LAND, comm);
    if (everywhere)
        MPI_Gatherv(words, lengths[rank], MPI_CHAR, all, lengths, lengths + ranks, MPI_CHAR, 0, comm);
    char detail[1536] = "";
    if (rank == 0 && everywhere)
        describe(all, (size_t)lengths[0], all + lengths[ranks + first], (size_t)lengths[first], first, detail,
                 sizeof detail);
    free(lengths);
    free(all);
    return im_fail(IM_EINVAL,
                   "the MPI ranks were not started alike: rank%s %s differ%s from rank 0%s%s%s: start "
                   "every rank with the same command in the same folder",
                   count > 1 ? "s" : "", list, count > 1 ? "" : "s", detail[0] ? " (" : "", detail,
                   detail[0] ? ")" : "");
}

int mpi_same_inputs(MPI_Comm comm, int count, char **args, const char *file)
{
    int ranks;
    MPI_Comm_size(comm, &ranks);
    uint64_t mine[RECORD] = {0}, *records = malloc(sizeof(uint64_t) * RECORD * (size_t)ranks);
    char *words = NULL;
    size_t length = 0;
    int status = records ? words_of(count, args, &words, &length) : im_fail(IM_ENOMEM, "the ranks' records");
    if ((status = mpi_collective_status(comm, status)) == IM_OK) {
        /* a file that a rank cannot read is reported after the arguments, which may explain it */
        int read = file ? file_hash(file, &mine[FILE_HASH]) : IM_OK;
        mine[WORDS_HASH] = fnv1a_add(FNV1A_START, words, length);
        mine[WORDS_LENGTH] = length;
        MPI_Allgather(mine, RECORD, MPI_UINT64_T, records, RECORD, MPI_UINT64_T, comm);
        char list[128];
        int first = 0, differing = differing_ranks(records, ranks, WORDS_HASH, list, sizeof list, &first);
        if (differing > 0)
            status = words_differ(comm, records, ranks, words, list, differing, first);
        else if ((status = mpi_collective_status(comm, read)) == IM_OK &&
                 (differing = differing_ranks(records, ranks, FILE_HASH, list, sizeof list, &first)) > 0)
            status = other_bytes(file, NULL, list, differing);
    }
    free(words);
    free(records);
    return status;
}

enum { DIGEST = IM_SHA256_HEX + 1 };

/* The SHA-256 of each of the count files, as text ended by '\0', one after another in *digests
 * (caller frees). */
static int input_digests(int count, const char *const *paths, char **digests)
{
    *digests = malloc((size_t)count * DIGEST + 1);
    int status = *digests ? IM_OK : im_fail(IM_ENOMEM, "the SHA-256 of %d input files", count);
    for (int i = 0; status == IM_OK && i < count; ++i)
        status = im_file_sha256(paths[i], *digests + (size_t)i * DIGEST);
    return status;
}

/* The first input whose digest differs between rank 0 and another rank (all: every rank's count
 * digests, rank after rank), named with its key and the ranks that differ; IM_OK when none does. */
static int first_differing_input(int count, const char *const *paths, const char *const *keys, const char *all,
                                 int ranks)
{
    for (int i = 0; i < count; ++i) {
        char list[128] = "";
        int differing = 0;
        for (int r = 1; r < ranks; ++r)
            if (strcmp(all + ((size_t)r * count + i) * DIGEST, all + (size_t)i * DIGEST) != 0)
                list_rank(list, sizeof list, ++differing, r);
        if (differing > 0)
            return other_bytes(paths[i], keys[i], list, differing);
    }
    return IM_OK;
}

/* IM_EINVAL naming the ranks whose source names another number of input files than rank 0's. */
static int counts_differ(const char *source, const int *counts, int ranks)
{
    char list[128] = "";
    int differing = 0, first = 0;
    for (int r = 1; r < ranks; ++r)
        if (counts[r] != counts[0]) {
            first = differing ? first : r;
            list_rank(list, sizeof list, ++differing, r);
        }
    if (differing == 0)
        return IM_OK;
    return im_fail(IM_EINVAL,
                   "%s names %d input files on rank %d, %d on rank 0 (rank%s %s differ%s): every "
                   "rank must read the same files",
                   source, counts[first], first, counts[0], differing > 1 ? "s" : "", list, differing > 1 ? "" : "s");
}

int mpi_same_files(MPI_Comm comm, const char *source, int count, const char *const *paths, const char *const *keys)
{
    int ranks;
    MPI_Comm_size(comm, &ranks);
    char *digests = NULL, *all = NULL;
    int *counts = malloc(sizeof *counts * (size_t)ranks);
    int status = counts ? input_digests(count, paths, &digests) : im_fail(IM_ENOMEM, "the ranks' input counts");
    if ((status = mpi_collective_status(comm, status)) == IM_OK) {
        MPI_Allgather(&count, 1, MPI_INT, counts, 1, MPI_INT, comm);
        status = counts_differ(source, counts, ranks);
    }
    if (status == IM_OK && count > 0) {
        all = malloc((size_t)ranks * count * DIGEST);
        if ((status = mpi_collective_status(comm, all ? IM_OK : im_fail(IM_ENOMEM, "the ranks' SHA-256"))) == IM_OK)
            MPI_Allgather(digests, count * DIGEST, MPI_CHAR, all, count * DIGEST, MPI_CHAR, comm);
        if (status == IM_OK)
            status = first_differing_input(count, paths, keys, all, ranks);
    }
    free(all);
    free(digests);
    free(counts);
    return status;
}
