/* The SHA-256 of a file (nettle), read in blocks. */
#include "io/checksum.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <errno.h>
#include <nettle/sha2.h>
#include <stdio.h>
#include <string.h>

int im_file_sha256(const char *path, char hex[IM_SHA256_HEX + 1])
{
    FILE *stream;
    long long size;
    int status = im_read_open(path, "rb", IM_READ_REGULAR, &stream, &size);
    if (status != IM_OK)
        return status;
    struct sha256_ctx context;
    sha256_init(&context);
    unsigned char block[65536];
    size_t got;
    while ((got = fread(block, 1, sizeof block, stream)) > 0)
        sha256_update(&context, got, block);
    int failed = ferror(stream), saved_errno = errno;
    fclose(stream);
    if (failed)
        return im_fail(IM_EIO, "%s: cannot read it for its checksum: %s", path, strerror(saved_errno));
    uint8_t digest[SHA256_DIGEST_SIZE];
    sha256_digest(&context, sizeof digest, digest);
    for (int i = 0; i < SHA256_DIGEST_SIZE; ++i)
        snprintf(hex + 2 * i, 3, "%02x", digest[i]);
    return IM_OK;
}
