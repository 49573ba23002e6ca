/* lt_mem.c - lt__memcpy and lt__memset, the core's only memory helpers (declared in lt_port.h).
 * Word loops when pointers are 4-byte aligned. Firmware targets route the memcpy/memset calls GCC
 * emits to these (firmware/targets/common/lt_rt.c). Builds: all.
 */
#include "lt/lt_port.h"

/* GCC turns byte loops into calls to memset/memcpy (-ftree-loop-distribute-patterns, on at -O2),
 * which inside memset itself would be infinite recursion; -fno-builtin does not stop it.
 * may_alias lets the word loops copy objects of any type without breaking strict aliasing. */
#if defined(__GNUC__) && !defined(__clang__)
#define LT__RT_FN __attribute__((optimize("no-tree-loop-distribute-patterns")))
#else
#define LT__RT_FN
#endif
#if defined(__GNUC__)
typedef uint32_t __attribute__((may_alias)) lt__rt_word_t;
#else
typedef uint32_t lt__rt_word_t;
#endif

LT__RT_FN void *lt__memcpy(void *LT_RESTRICT dst, const void *LT_RESTRICT src, size_t n)
{
    unsigned char *d = (unsigned char *)dst;
    const unsigned char *s = (const unsigned char *)src;

    /* Word copy only when both pointers share 4-byte alignment: unaligned word access traps on
     * some cores and is slow on others. */
    if ((((uintptr_t)d | (uintptr_t)s) & 3u) == 0) {
        lt__rt_word_t *dw = (lt__rt_word_t *)(void *)d;
        const lt__rt_word_t *sw = (const lt__rt_word_t *)(const void *)s;
        /* four words per step: the lane vectors GCC copies through here are 64 or 128 bytes */
        for (; n >= 16; n -= 16) {
            lt__rt_word_t a = sw[0], b = sw[1], c = sw[2], e = sw[3];
            dw[0] = a;
            dw[1] = b;
            dw[2] = c;
            dw[3] = e;
            dw += 4;
            sw += 4;
        }
        for (; n >= 4; n -= 4)
            *dw++ = *sw++;
        d = (unsigned char *)dw;
        s = (const unsigned char *)sw;
    }
    while (n--)
        *d++ = *s++;
    return dst;
}

LT__RT_FN void *lt__memset(void *dst, int c, size_t n)
{
    unsigned char *d = (unsigned char *)dst;
    unsigned char b = (unsigned char)c;

    while (n != 0 && ((uintptr_t)d & 3u) != 0) {
        *d++ = b;
        n--;
    }
    if (n >= 4) {
        lt__rt_word_t *dw = (lt__rt_word_t *)(void *)d;
        uint32_t w = (uint32_t)b * 0x01010101u;
        for (; n >= 4; n -= 4)
            *dw++ = w;
        d = (unsigned char *)dw;
    }
    while (n--)
        *d++ = b;
    return dst;
}

