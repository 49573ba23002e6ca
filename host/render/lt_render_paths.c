/* lt_render_paths.c - the object-space operations of each numeric path (lt_render_ops_t,
 * lt_path_ops.h): lt_render_path.inc instantiated once per path with that path's generic names.
 * Adding a path: its lt_path_<suffix>.h, three lines here, its entry in lt_paths.c. Host only.
 */
#include "render/lt_path_ops.h"
#include "io/lt_fx_float.h"

#include <string.h>

/* s15.16 */
#include "render/lt_path_q16.h"
#include "render/lt_render_path.inc"
const lt_render_ops_t lt_render_ops_q16 = LT_RENDER_OPS;
#include "render/lt_path_undef.h"

/* float32 */
#include "render/lt_path_f32.h"
#include "render/lt_render_path.inc"
const lt_render_ops_t lt_render_ops_f32 = LT_RENDER_OPS;
#include "render/lt_path_undef.h"
