/* lt_rt.c - freestanding runtime for firmware targets: the memory functions GCC may emit calls to
 * (memcpy, memset, memmove, memcmp) routed to the core's lt__memcpy/lt__memset
 * (firmware/core/numerics/lt_mem.c), and the target-independent
 * UART output helpers of lt_fw.h (strings, decimal, hex). No libc is linked (-nostdlib).
 * Builds: firmware (cm4, cm55, rv32); plain C99 plus GCC attributes where GCC needs them.
 */
#include <stddef.h>
#include <stdint.h>

#include "lt_fw.h"

/* GCC turns byte loops into calls to memset/memcpy (-ftree-loop-distribute-patterns, on at -O2),
 * which inside memset itself would be infinite recursion; -fno-builtin does not stop it. */
#if defined(__GNUC__) && !defined(__clang__)
#define LT__RT_FN __attribute__((optimize("no-tree-loop-distribute-patterns")))
#else
#define LT__RT_FN
#endif

/* The C library names, declared here because no <string.h> is used. */
void *memcpy(void *LT_RESTRICT dst, const void *LT_RESTRICT src, size_t n);
void *memset(void *dst, int c, size_t n);
void *memmove(void *dst, const void *src, size_t n);
int memcmp(const void *a, const void *b, size_t n);

LT__RT_FN void *memcpy(void *LT_RESTRICT dst, const void *LT_RESTRICT src, size_t n)
{
    return lt__memcpy(dst, src, n);
}

LT__RT_FN void *memset(void *dst, int c, size_t n)
{
    return lt__memset(dst, c, n);
}

LT__RT_FN void *memmove(void *dst, const void *src, size_t n)
{
    unsigned char *d = (unsigned char *)dst;
    const unsigned char *s = (const unsigned char *)src;

    /* Comparing unrelated pointers is undefined in C; comparing their integer values is not. */
    if ((uintptr_t)d <= (uintptr_t)s || (uintptr_t)d >= (uintptr_t)s + n) {
        while (n--)
            *d++ = *s++;
    } else {
        d += n;
        s += n;
        while (n--)
            *--d = *--s;
    }
    return dst;
}

LT__RT_FN int memcmp(const void *a, const void *b, size_t n)
{
    const unsigned char *p = (const unsigned char *)a;
    const unsigned char *q = (const unsigned char *)b;

    for (; n != 0; n--, p++, q++) {
        if (*p != *q)
            return (int)*p - (int)*q;
    }
    return 0;
}

void lt_fw_puts(const char *s)
{
    while (*s != '\0')
        lt_fw_putc((unsigned char)*s++);
}

void lt_fw_put_u32(uint32_t v)
{
    char buf[10]; /* 4294967295 has 10 digits */
    unsigned n = 0;

    do {
        buf[n++] = (char)('0' + (v % 10u));
        v /= 10u;
    } while (v != 0);
    while (n != 0)
        lt_fw_putc(buf[--n]);
}

void lt_fw_put_hex32(uint32_t v)
{
    static const char digits[] = "0123456789abcdef";
    int shift;

    lt_fw_putc('0');
    lt_fw_putc('x');
    for (shift = 28; shift >= 0; shift -= 4)
        lt_fw_putc(digits[(v >> shift) & 0xFu]);
}

/* ---- stack high-water mark -------------------------------------------------------------------- */

extern uint32_t lt__fw_stack_limit[], lt__fw_stack_top[];
extern uint32_t lt__fw_data_start[], lt__fw_data_end[], lt__fw_bss_start[], lt__fw_bss_end[];

#define LT__FW_PAINT 0x5AA5C33Cu

LT__RT_FN void lt__fw_stack_paint(void)
{
    volatile uint32_t *p = (volatile uint32_t *)lt__fw_stack_limit;
    volatile char here = 0;
    uintptr_t end = ((uintptr_t)&here - 256u) & ~(uintptr_t)3u;
    while ((uintptr_t)p < end)
        *p++ = LT__FW_PAINT;
}

uint32_t lt_fw_stack_used(void)
{
    const volatile uint32_t *p = (const volatile uint32_t *)lt__fw_stack_limit;
    uintptr_t top = (uintptr_t)lt__fw_stack_top;
    while ((uintptr_t)p < top && *p == LT__FW_PAINT)
        p++;
    return (uint32_t)(top - (uintptr_t)p);
}

uint32_t lt_fw_stack_size(void)
{
    return (uint32_t)((uintptr_t)lt__fw_stack_top - (uintptr_t)lt__fw_stack_limit);
}

static int lt__fw_ram_on = 1;

void lt_fw_ram_report(int on) { lt__fw_ram_on = on; }

void lt__fw_report_ram(void)
{
    if (!lt__fw_ram_on)
        return;
    lt_fw_puts("ram: stack ");
    lt_fw_put_u32(lt_fw_stack_used());
    lt_fw_puts(" of ");
    lt_fw_put_u32(lt_fw_stack_size());
    lt_fw_puts(" bytes, static ");
    lt_fw_put_u32((uint32_t)((uintptr_t)lt__fw_data_end - (uintptr_t)lt__fw_data_start) +
                  (uint32_t)((uintptr_t)lt__fw_bss_end - (uintptr_t)lt__fw_bss_start));
    lt_fw_puts(" bytes (.data + .bss)\n");
}

/* The stage marks (lt_fw.h): in its own function so the plugin instruments only this store. */
volatile uint32_t lt_fw_stage_slots[16];

LT_NOINLINE void lt_fw_stage(uint32_t k)
{
    lt_fw_stage_slots[k & 15u] = k;
}
