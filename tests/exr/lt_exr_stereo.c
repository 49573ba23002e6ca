/* lt_exr_stereo.c - writes the multi-part / multi-view EXR test files of tests/unit/lt_exr_testlib.h
 * for the CLI tests (tests/run.d/cli.sh, reproject.sh). Test tool, not shipped.
 *   lt-exr-stereo stereo|split|nomv|single OUT.exr    a synthetic 24x16 stereo file
 *   lt-exr-stereo widedisp|fardisp OUT.exr             24x16 of one eye in a display window over
 *                                                      LT_EXR_MAX_DIM (20000 wide; 2^30 - 1 square)
 *   lt-exr-stereo ctlview OUT.exr                      "stereo" whose right view is named
 *                                                      "right\n\033[31m" (control bytes in a name)
 *   lt-exr-stereo farwin OUT.exr                       24x16 of one eye, its data window at
 *                                                      (10^6, 10^6), outside the 32x24 display window
 *   lt-exr-stereo beachball OUT.exr SRC.exr            the shared single-part Beachball frame as a
 *                                                      2-part stereo file (part 0 left, 1 right)
 * Exit 0, 1 with a one-line error, 2 on usage.
 */
#include <stdio.h>
#include <string.h>

#include "lt_exr_testlib.h"

int main(int argc, char **argv)
{
    lt_diag_t diag;
    int rc;
    if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        printf("usage: lt-exr-stereo stereo|split|nomv|single|widedisp|fardisp|farwin|ctlview OUT.exr\n"
               "       lt-exr-stereo beachball OUT.exr SRC.exr\n");
        return 0;
    }
    if (argc < 3 || (strcmp(argv[1], "beachball") == 0) != (argc == 4) || argc > 4) {
        fprintf(stderr, "usage: lt-exr-stereo stereo|split|nomv|single|widedisp|fardisp|farwin|ctlview OUT.exr | "
                        "beachball OUT.exr SRC.exr\n");
        return 2;
    }
    if (strcmp(argv[1], "beachball") == 0)
        rc = ltx_beachball_stereo(argv[3], argv[2], &diag);
    else
        rc = ltx_write_kind(argv[2], argv[1], &diag);
    if (rc != 0) {
        fprintf(stderr, "lt-exr-stereo: %s\n", diag.msg);
        return 1;
    }
    return 0;
}
