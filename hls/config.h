/*
 * Synthesis configuration of hls/: which units and paths the design contains. The defaults are the
 * general pipeline; `saarcor profile SCENE -o hls/config_NAME.h` writes a header for one scene
 * that turns off what it does not need, and the build includes it first (-include, e.g.
 * `make hls-check CONFIG=NAME`). A configured design renders that scene bit for bit like the
 * general one (docs/hls.md); the simulator is always built general.
 */
#ifndef SAARCOR_CONFIG_H
#define SAARCOR_CONFIG_H

#ifndef SAARCOR_CFG_TOP_LEVEL
#define SAARCOR_CFG_TOP_LEVEL 1    /* top-level kd-tree traversal and its leaf lists */
#endif
#ifndef SAARCOR_CFG_TEXTURES
#define SAARCOR_CFG_TEXTURES 1     /* texture coordinates and the bilinear filter */
#endif
#ifndef SAARCOR_CFG_SECONDARY
#define SAARCOR_CFG_SECONDARY 1    /* reflection and transmission rays (T_R path) */
#endif
#ifndef SAARCOR_CFG_REFRACTION
#define SAARCOR_CFG_REFRACTION 1   /* refracted directions (sqrt, Snell) */
#endif
#ifndef SAARCOR_CFG_SHADOWS
#define SAARCOR_CFG_SHADOWS 1      /* shadow rays */
#endif
#ifndef SAARCOR_CFG_SPOT_LIGHTS
#define SAARCOR_CFG_SPOT_LIGHTS 1  /* spot cone factor */
#endif
#ifndef SAARCOR_CFG_ORTHOGRAPHIC
#define SAARCOR_CFG_ORTHOGRAPHIC 1 /* orthographic primary rays */
#endif
#ifndef SAARCOR_CFG_EDGE_EPS
#define SAARCOR_CFG_EDGE_EPS 0     /* robust edge tests (docs/stress.md): k > 0 widens every triangle's
                                      barycentric bounds by eps = 2^-k (u, v >= -eps, u + v <= 1 + eps);
                                      0: the paper's exact bounds */
#endif
#ifndef SAARCOR_CFG_SHARED_EDGE_EPS
#define SAARCOR_CFG_SHARED_EDGE_EPS F24_MAN_BITS /* k > 0 widens only the bounds on edges a triangle
                                      shares with another of its object by 2^-k (one ulp at 1 by
                                      default: closes the cracks between them, silhouettes stay;
                                      docs/stress.md); 0: exact */
#endif
#ifndef SAARCOR_CFG_MAX_DEPTH
#define SAARCOR_CFG_MAX_DEPTH 8    /* secondary levels the ray stack holds */
#endif

#endif
