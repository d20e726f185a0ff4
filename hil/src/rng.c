/* xoshiro256** and Box-Muller; see hil/rng.h. */
#include <math.h>
#include "hil/rng.h"

static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

void hil_rng_seed(struct hil_rng *r, uint64_t seed)
{
    int i;
    for (i = 0; i < 4; i++) { /* splitmix64 expands the seed into the state */
        uint64_t z = (seed += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        r->s[i] = z ^ (z >> 31);
    }
    r->has_spare = 0;
    r->spare = 0.0;
}

uint64_t hil_rng_u64(struct hil_rng *r)
{
    uint64_t *s = r->s;
    uint64_t result = rotl(s[1] * 5, 7) * 9;
    uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return result;
}

double hil_rng_uniform(struct hil_rng *r) { return (double)(hil_rng_u64(r) >> 11) * 0x1.0p-53; }

double hil_rng_normal(struct hil_rng *r)
{
    double u1, u2, m;
    if (r->has_spare) {
        r->has_spare = 0;
        return r->spare;
    }
    do {
        u1 = hil_rng_uniform(r);
    } while (u1 <= 0.0);
    u2 = hil_rng_uniform(r);
    m = sqrt(-2.0 * log(u1));
    r->spare = m * sin(2.0 * M_PI * u2);
    r->has_spare = 1;
    return m * cos(2.0 * M_PI * u2);
}
