/* Uses the installed headers and libraries: a resampling round trip (library) and a refused
 * call into the memory port (port library). Prints the number type it was compiled for. */
#include <stdio.h>
#include "pft/pft.h"
#include "pft/pft_port_mem.h"

int main(void)
{
    pft_rng_t rng;
    pft_weight_t w[4] = {PFT_W_ONE / 8, PFT_W_ONE / 8, PFT_W_ONE / 4, PFT_W_ONE / 2};
    uint32_t idx[8];
    pft_rng_seed(&rng, 7u);
    if (pft_resample(PFT_RESAMPLE_SYSTEMATIC, w, 4, idx, 8, &rng, NULL, 0) != PFT_OK) {
        return 1;
    }
    if (pft_mem_source_init(NULL, NULL) == PFT_OK) {
        return 3;
    }
    printf("pftrack %s (%s, numeric %s): idx[7] = %u\n", PFT_VERSION_STRING, PFT_LIBRARY_NAME,
           PFT_NUMERIC_NAME, (unsigned)idx[7]);
    return idx[7] == 3u ? 0 : 2;
}
