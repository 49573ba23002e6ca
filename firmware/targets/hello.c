/* hello.c - firmware smoke test: UART output, decimal/hex printing, .data copy and .bss zeroing,
 * the memory functions, the FPU (and MVE on cm55), the tick counter, and the exit code
 * (7, or LT_FW_HELLO_RC). Expected output is checked by firmware/targets/smoke.sh.
 * Builds: firmware (cm4, cm55, rv32) via firmware/targets/smoke.mk.
 */
#include <stdint.h>

#include "lt_fw.h"

#if defined(__ARM_FEATURE_MVE)
#include <arm_mve.h>
#endif

#ifndef LT_FW_HELLO_RC
#define LT_FW_HELLO_RC 7
#endif

static volatile uint32_t data_word = 0x12345678u; /* checks the .data copy */
static volatile uint32_t bss_words[64];                  /* checks .bss zeroing */

typedef struct {
    uint32_t w[24]; /* large enough that GCC copies it with memcpy */
} blob_t;

static LT_NOINLINE void blob_copy(blob_t *dst, const blob_t *src)
{
    *dst = *src;
}

static int check_rt(void)
{
    blob_t a, b;
    unsigned char buf[40];
    uint32_t i;

    for (i = 0; i < 24u; i++)
        a.w[i] = i * 2654435761u;
    blob_copy(&b, &a);
    if (b.w[23] != a.w[23] || b.w[0] != 0u)
        return 0;
    lt__memset(buf, 0xA5, sizeof buf);
    lt__memset(buf + 3, 0, 17); /* unaligned head, word body, tail */
    if (buf[2] != 0xA5u || buf[3] != 0 || buf[19] != 0 || buf[20] != 0xA5u)
        return 0;
    for (i = 0; i < sizeof buf; i++)
        buf[i] = (unsigned char)i;
    lt__memcpy(buf + 20, buf + 1, 9); /* unaligned copy */
    if (buf[20] != 1u || buf[28] != 9u || buf[29] != 29u)
        return 0;
    return 1;
}

/* A fixed amount of work: tick deltas around it are identical from run to run under -icount. */
static LT_NOINLINE uint32_t work(uint32_t n)
{
    volatile uint32_t acc = 1;
    uint32_t i;

    for (i = 0; i < n; i++)
        acc = acc * 1664525u + 1013904223u;
    return acc;
}

int main(void)
{
    volatile float f = 1.5f;
    uint64_t t0, t1;
    uint32_t i, bss_or = 0;

    lt_fw_puts("hello from " LT_FW_TARGET_NAME "\n");

    lt_fw_puts("u32: ");
    lt_fw_put_u32(0);
    lt_fw_putc(' ');
    lt_fw_put_u32(1234567890u);
    lt_fw_putc(' ');
    lt_fw_put_u32(4294967295u);
    lt_fw_puts("\nhex: ");
    lt_fw_put_hex32(0);
    lt_fw_putc(' ');
    lt_fw_put_hex32(0xDEADBEEFu);
    lt_fw_putc('\n');

    for (i = 0; i < 64u; i++)
        bss_or |= bss_words[i];
    lt_fw_puts(data_word == 0x12345678u && bss_or == 0 ? "data/bss: ok\n" : "data/bss: BAD\n");
    lt_fw_puts(check_rt() ? "rt: ok\n" : "rt: BAD\n");

    /* On Arm this faults (NOCP) unless start-up enabled the FPU; on rv32 it is soft-float. */
    f = f * 2.5f;
    lt_fw_puts("fpu: ");
    lt_fw_put_u32((uint32_t)(f * 100.0f));
    lt_fw_putc('\n');

#if defined(__ARM_FEATURE_MVE)
    {
        static const int32_t in[4] = { 1, 2, 3, 4 };
        int32x4_t v = vld1q_s32(in);
        v = vaddq_s32(v, v);
        lt_fw_puts("mve: ");
        lt_fw_put_u32((uint32_t)vaddvq_s32(v));
        lt_fw_putc('\n');
    }
#endif

    t0 = lt_fw_ticks();
    (void)work(100000u);
    t1 = lt_fw_ticks();
    lt_fw_puts("ticks: ");
    lt_fw_put_u32((uint32_t)(t1 - t0));
    lt_fw_puts(" at ");
    lt_fw_put_u32((uint32_t)t0);
    lt_fw_putc('\n');

    lt_fw_puts("exit: ");
    lt_fw_put_u32(LT_FW_HELLO_RC);
    lt_fw_putc('\n');
    return LT_FW_HELLO_RC;
}
