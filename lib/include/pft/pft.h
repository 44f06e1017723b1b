/**
 * @file pft.h
 * @brief Umbrella header: everything a firmware needs from pftrack.
 */
#ifndef PFT_H
#define PFT_H
#include "pft/pft_config.h"
#include "pft/pft_types.h"
#include "pft/pft_real.h"
#include "pft/pft_rng.h"
#include "pft/pft_resample.h"
#include "pft/pft_workspace.h"
#include "pft/pft_kalman.h"
#include "pft/pft_tbd.h"
#include "pft/pft_tbd_scene.h"
#include "pft/pft_pf.h"
#include "pft/pft_pf_models.h"
#include "pft/pft_tsa.h"
#include "pft/pft_pte.h"
#include "pft/pft_pre.h"
#endif
