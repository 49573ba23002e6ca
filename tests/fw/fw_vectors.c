/* fw_vectors.c - firmware driver of the cross-target test vectors: the same lines as the host
 * driver, over the board UART, then exit 0 through semihosting. Freestanding.
 */
#include "lt_fw.h"
#include "lt_vec.h"

static void put(const char *line) { lt_fw_puts(line); }

int main(void)
{
    int n = lt_vec_run(put);
    lt_fw_puts("groups ");
    lt_fw_put_u32((uint32_t)n);
    lt_fw_puts("\n");
    return 0;
}
