/* Seeded pseudo-random numbers for the rig's effects: xoshiro256** (Blackman
 * and Vigna 2018) seeded through splitmix64, Gaussian by Box-Muller. Same seed,
 * same sequence on every platform, so every run is reproducible from the
 * seeds recorded in its metadata. */
#ifndef HIL_RNG_H
#define HIL_RNG_H
#include <stdint.h>

struct hil_rng { uint64_t s[4]; int has_spare; double spare; };

void hil_rng_seed(struct hil_rng *r, uint64_t seed);
uint64_t hil_rng_u64(struct hil_rng *r);
/* Uniform in [0, 1) with 53 random bits. */
double hil_rng_uniform(struct hil_rng *r);
/* Standard normal N(0, 1). */
double hil_rng_normal(struct hil_rng *r);

#endif
