/* lt_rate.h - a ray rate in a unit that fits, for every report that prints one (the cycle model's
 * report, lanetrace run, reproject and shadows, native and simulated): "12.3 Mrays/s", "456
 * krays/s", "7.89 rays/s", 3 significant digits, so a slow run never prints "0.00 Mrays/s".
 * Header only (the host programs and the cycle model both use it). */
#ifndef LT_RATE_H
#define LT_RATE_H

#include <stdio.h>

#define LT_RATE_TEXT 24 /* bytes of the text, the NUL included */

/* rays per second -> buf; "0 rays/s" for zero, "n/a" for a negative or non-finite rate (no time
 * measured). Returns buf. */
static inline const char *lt_rate_text(double r, char buf[LT_RATE_TEXT])
{
    static const char *const unit[] = {"rays/s", "krays/s", "Mrays/s", "Grays/s", "Trays/s"};
    int u = 0;
    if (!(r >= 0.0) || r > 1e300) {
        snprintf(buf, LT_RATE_TEXT, "n/a");
        return buf;
    }
    if (r == 0.0) {
        snprintf(buf, LT_RATE_TEXT, "0 rays/s");
        return buf;
    }
    /* the unit after rounding to 3 digits: 999.6 krays/s prints as 1.00 Mrays/s */
    while (u < 4 && r >= 999.5) {
        r /= 1000.0;
        u++;
    }
    snprintf(buf, LT_RATE_TEXT, r >= 99.95 ? "%.0f %s" : r >= 9.995 ? "%.1f %s" : "%.2f %s", r,
             unit[u]);
    return buf;
}

#endif /* LT_RATE_H */
