/* reproj_fw_packets.c - build/fw/<T>/reproj-bb-packets.elf: reproj_fw.c tracing packets of 16
 * through the lane model (lt_qt_trace16_q30) instead of single rays, for the instruction tables of
 * docs/firmware.md (tools/fw_rays.sh) and the check that both walks print the host's lines
 * (tests/run.d/reproj_blob.sh). Builds: firmware (cm4, cm55, rv32).
 */
#define LT_RPFW_SINGLE 0
#include "reproj_fw.c"
