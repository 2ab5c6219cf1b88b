/* Times generated `inverse_dynamics` code (screwdyn symbolic --quantity torque --format c) the
 * way bench/pinocchio_bench.cpp times Pinocchio's rnea: median ns per call over BATCHES batches
 * of CALLS calls, cycling through 1000 random states (q in [-pi, pi], v and a in [-1, 1]).
 * Compile with the generated file: cc -O3 -march=native -DGENERATED='"gen.c"' symbolic_bench.c -lm
 * Usage: symbolic_bench NQ BATCHES CALLS → {"ns_per_call": x} */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include GENERATED

#define NSTATES 1000
#define MAXQ 16

static double now_ns(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return 1e9 * (double)t.tv_sec + (double)t.tv_nsec;
}

static int cmp(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static unsigned long long seed = 42;
static double uniform(double lo, double hi) {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * ((double)(seed >> 11) / 9007199254740992.0);
}

int main(int argc, char **argv) {
    if (argc != 4) {
        fprintf(stderr, "usage: symbolic_bench NQ BATCHES CALLS\n");
        return 2;
    }
    int n = atoi(argv[1]), batches = atoi(argv[2]), calls = atoi(argv[3]);
    if (n < 1 || n > MAXQ || batches < 1 || calls < 1) return 2;
    static double q[NSTATES][MAXQ], v[NSTATES][MAXQ], a[NSTATES][MAXQ];
    for (int k = 0; k < NSTATES; k++)
        for (int i = 0; i < n; i++) {
            q[k][i] = uniform(-3.141592653589793, 3.141592653589793);
            v[k][i] = uniform(-1.0, 1.0);
            a[k][i] = uniform(-1.0, 1.0);
        }
    double out[MAXQ], sink = 0.0;
    double *per_call = malloc(sizeof(double) * (size_t)batches);
    for (int b = -1; b < batches; b++) {
        double t0 = now_ns();
        for (int c = 0; c < calls; c++) {
            int k = c % NSTATES;
            inverse_dynamics(q[k], v[k], a[k], out);
            __asm__ volatile("" : : "g"(out) : "memory");
        }
        double t1 = now_ns();
        sink += out[0];
        if (b >= 0) per_call[b] = (t1 - t0) / calls;
    }
    qsort(per_call, (size_t)batches, sizeof(double), cmp);
    double med = batches % 2 ? per_call[batches / 2]
                             : 0.5 * (per_call[batches / 2 - 1] + per_call[batches / 2]);
    printf("{\"ns_per_call\": %.2f, \"sink\": %g}\n", med, sink != sink ? 0.0 : 0.0);
    free(per_call);
    return 0;
}
