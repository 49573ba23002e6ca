/* vec_host.c - host driver of the cross-target test vectors: prints every group's hash line.
 * Built as build/<variant>/lt-vectors for host, sim, asan and avx2. `lt-vectors --backend` prints
 * the lane backend the build compiled (lt_v16_x86.h: avx512, avx2 or portable) instead. Host only.
 */
#include <stdio.h>
#include <string.h>
#include "lt_vec.h"
#include "lt/lt_v16.h"

static void put(const char *line) { fputs(line, stdout); }

int main(int argc, char **argv)
{
    int n;
    if (argc == 2 && strcmp(argv[1], "--backend") == 0) {
        printf("%s\n", LT_LANES_BACKEND);
        return 0;
    }
    n = lt_vec_run(put);
    printf("groups %d\n", n);
    return 0;
}
