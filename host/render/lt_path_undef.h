/* lt_path_undef.h - removes the generic LTH_* names of lt_path_<suffix>.h so the next path can
 * define them. Host only.
 */
#undef LTH_FN
#undef LTH_TY
#undef LTH_MID
#undef LTH_TRIS
#undef LTH_T
#undef LTH_D
#undef LTH_POS
#undef LTH_DIR
#undef LTH_POS_D
#undef LTH_DIR_D
#undef LTH_TMAX1
#undef LTH_HAS_BVHQ
#undef LTH_IF_BVHQ
#undef LTH_SCENE_CHECK
#undef LTH_W
#undef LTH_W_BYTES
#undef LTH_XY_D
#undef LTH_W_D
#undef LTH_REPROJ_SETUP
#undef LTH_V
#undef LTH_VD
#undef LTH_VSET1
#undef LTH_VDSET1
#undef LTH_VMUL
#undef LTH_GATHER_D
#undef LTH_MADD_D
#undef LTH_FLIP_D
#undef LTH_AWAY
#undef LTH_PRAY_DIR
#undef LTH_VIS16
#undef LTH_VISN
#undef LTH_NORMAL_WORD
#undef LTH_FRONT
#undef LTH_VERT_D
#undef LTH_PVIEW
