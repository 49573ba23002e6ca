/* lt.h - umbrella header of the lanetrace core: formats, lane model, cost hook, kernels.
 * Builds: all.
 */
#ifndef LT_H
#define LT_H

#include "lt_config.h"
#include "lt_port.h"
#include "lt_status.h"
#include "lt_cost.h"
#include "lt_fx.h"
#include "lt_v16.h"
#include "lt_isect.h"
#include "lt_bvh.h"
#include "lt_bvh8.h"
#include "lt_wt.h"
#include "lt_kd.h"
#include "lt_grid.h"
#include "lt_qt.h"
#include "lt_stream.h"

#endif /* LT_H */
