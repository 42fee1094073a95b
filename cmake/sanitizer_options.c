/* Built into every executable of the sanitizer build (IM_SANITIZE): the defaults AddressSanitizer reads
 * before ASAN_OPTIONS, which still overrides them key by key.
 *
 * intercept_tls_get_addr=0: up to GCC 13 the runtime's __tls_get_addr interceptor takes a dynamic TLS block
 * that happens to start 16 bytes past a 4096-byte boundary for a glibc-2.19 block with a header, and reads the
 * two words before it as the block's start and size (glibc has had no such header since 2.25). LeakSanitizer's
 * tracer then scans that made-up range at exit and dies ("Tracer caught signal 11", exit 1, no leak reported).
 * Mesa's drivers, opened with dlopen, have such blocks: about one EGL-rendering run in 150 failed so here (CI's
 * cli_limits, 2026-11-28). Fixed upstream in LLVM 17; Debian 12's GCC 12 has the old code. */
const char *__asan_default_options(void);

const char *__asan_default_options(void) { return "intercept_tls_get_addr=0"; }
