/* lt_vec.h - the cross-target test vectors: deterministic inputs (extremes + xorshift32) through
 * every numeric op, lane op and kernel, folded into one FNV-1a hash per group. The same code runs on
 * the host (host, sim, asan builds) and under QEMU (cm4, cm55, rv32); make test requires every
 * build to print identical lines, equal to tests/golden/vectors.txt. Freestanding.
 */
#ifndef LT_VEC_H
#define LT_VEC_H

/* Run every group; put() receives each output line (with '\n'). Returns the number of groups. */
int lt_vec_run(void (*put)(const char *line));

#endif /* LT_VEC_H */
