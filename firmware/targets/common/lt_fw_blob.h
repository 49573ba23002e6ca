/* lt_fw_blob.h - the blob a firmware image links as read-only data (lt_fw_blob.S): its bytes are
 * lt_fw_blob[0 .. lt_fw_blob_end - lt_fw_blob). Images name the file with FW_BLOB_<image> in
 * firmware/firmware.mk. Builds: firmware only.
 */
#ifndef LT_FW_BLOB_H
#define LT_FW_BLOB_H

#include <stddef.h>
#include <stdint.h>

extern const uint8_t lt_fw_blob[];
extern const uint8_t lt_fw_blob_end[];

/* Bytes in the blob. */
static inline size_t lt_fw_blob_size(void)
{
    return (size_t)(lt_fw_blob_end - lt_fw_blob);
}

#endif /* LT_FW_BLOB_H */
