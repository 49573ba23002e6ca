/* vec_host.c - host driver of the cross-target test vectors: prints every group's hash line.
 * Built as build/<variant>/lt-vectors for host, sim and asan. Host only.
 */
#include <stdio.h>
#include "lt_vec.h"

static void put(const char *line) { fputs(line, stdout); }

int main(void)
{
    int n = lt_vec_run(put);
    printf("groups %d\n", n);
    return 0;
}
