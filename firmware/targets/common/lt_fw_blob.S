/* lt_fw_blob.S - links one prepared, position-independent data blob (a scene or depth image the
 * host tools wrote, build/gen/...) into a firmware image as read-only data: flash on the boards
 * (cm4 SSRAM1 code region, cm55 ITCM), never RAM the program counts as its own. The file is named
 * at assembly time: -DLT_FW_BLOB_FILE='"path"'. Symbols: lt_fw_blob (64-byte aligned) and
 * lt_fw_blob_end (firmware/targets/common/lt_fw_blob.h). Builds: firmware only.
 */
    .section .rodata.lt_fw_blob, "a", %progbits
    .balign 64
    .global lt_fw_blob
lt_fw_blob:
    .incbin LT_FW_BLOB_FILE
    .global lt_fw_blob_end
lt_fw_blob_end:
    .byte 0
