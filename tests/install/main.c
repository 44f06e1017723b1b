/* Uses the installed headers and library: a workspace-sized resampling round trip. */
#include <stdio.h>
#include "pft/pft.h"

int main(void)
{
    pft_rng_t rng;
    pft_weight_t w[4] = {PFT_W_ONE / 8, PFT_W_ONE / 8, PFT_W_ONE / 4, PFT_W_ONE / 2};
    uint32_t idx[8];
    pft_rng_seed(&rng, 7u);
    if (pft_resample(PFT_RESAMPLE_SYSTEMATIC, w, 4, idx, 8, &rng, NULL, 0) != PFT_OK) {
        return 1;
    }
    printf("pftrack %s (%s): idx[7] = %u\n", PFT_VERSION_STRING, PFT_LIBRARY_NAME, (unsigned)idx[7]);
    return idx[7] == 3u ? 0 : 2;
}
