/* One onboard step of the exported C timed, or counted: the C of a model
 * (this checkout's `dtg-vib export --lang c`, or 5b6a72d's) on the same
 * seeded inputs as harness.rs: an LCG from seed 7, per sample each gyro in
 * -15 ... 15 deg/h, each accelerometer in -0.3 ... 0.3 g (+1 g on every
 * third).
 *
 *     cc -O2 -std=c99 dtg_model.c harness.c -lm -o harness
 *     ./harness          median ns per step of 1001 batches of 100 steps
 *     ./harness STEPS    that many steps, a checksum (for callgrind)
 */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "dtg_model.h"

/* 5b6a72d's C of the paper's layout names no sizes: six gyros, three
 * accelerometers. */
#ifndef DTG_N_GYROS
#define DTG_N_GYROS 6
#define DTG_N_ACCELS 3
#endif

static int cmp(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv) {
    enum { BATCHES = 1001, PER = 100 };
    static double gyro[PER][DTG_N_GYROS], acc[PER][DTG_N_ACCELS];
    static double times[BATCHES];
    double rate[DTG_N_GYROS], a_out[DTG_N_ACCELS], extra[DTG_N_EXTRA + 1] = {0}, sink = 0;
    static dtg_state s;
    long steps = argc > 1 ? atol(argv[1]) : 0, n;
    int b, i, k;
    unsigned long seed = 7;
    for (i = 0; i < PER; i++) {
        for (k = 0; k < DTG_N_GYROS; k++) {
            seed = seed * 6364136223846793005UL + 1;
            gyro[i][k] = 30.0 * ((seed >> 11) / 9007199254740992.0) - 15.0;
        }
        for (k = 0; k < DTG_N_ACCELS; k++) {
            seed = seed * 6364136223846793005UL + 1;
            acc[i][k] = (k % 3 == 2) + 0.6 * ((seed >> 11) / 9007199254740992.0) - 0.3;
        }
    }
    dtg_init(&s);
    for (i = 0; i < PER; i++) dtg_step(&s, gyro[i], acc[i], extra, rate, a_out);
    if (steps > 0) {
        for (n = 0; n < steps; n++)
            if (dtg_step(&s, gyro[n % PER], acc[n % PER], extra, rate, a_out)) sink += rate[0];
        printf("%.17g\n", sink);
        return 0;
    }
    for (b = 0; b < BATCHES; b++) {
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        for (i = 0; i < PER; i++) {
            dtg_step(&s, gyro[i], acc[i], extra, rate, a_out);
            sink += rate[0];
        }
        clock_gettime(CLOCK_MONOTONIC, &t1);
        times[b] = ((t1.tv_sec - t0.tv_sec) * 1e9 + (t1.tv_nsec - t0.tv_nsec)) / PER;
    }
    qsort(times, BATCHES, sizeof times[0], cmp);
    printf("%.1f %g\n", times[BATCHES / 2], sink);
    return 0;
}
