/* MuJoCo's own C loop for bench/sim_vs_mujoco.sh: the same passive run as
 * crates/screwdyn/examples/sim_bench.rs and bench/sim_vs_mujoco.py (1 kHz, RK4, contacts and
 * joint limits disabled, released from rest at q0), timed around a plain `mj_step` loop with no
 * Python in it.
 *
 * Usage: mj_step_loop MODEL.urdf NSTEP REPEAT q0_1,q0_2,...
 * Prints one JSON line: {"steps": N, "seconds": [...], "median_s": s, "final_q": [...]}.
 * Built by sim_vs_mujoco.sh against the libmujoco and headers shipped in the mujoco wheel. */
#include <mujoco/mujoco.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmp(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

int main(int argc, char** argv) {
  if (argc != 5) {
    fprintf(stderr, "usage: %s MODEL.urdf NSTEP REPEAT q0,...\n", argv[0]);
    return 2;
  }
  char err[1000] = "";
  mjModel* m = mj_loadXML(argv[1], NULL, err, sizeof err);
  if (!m) {
    fprintf(stderr, "mj_step_loop: cannot load %s: %s\n", argv[1], err);
    return 2;
  }
  long nstep = atol(argv[2]);
  int repeat = atoi(argv[3]);
  if (nstep <= 0 || repeat <= 0 || repeat > 1000) {
    fprintf(stderr, "mj_step_loop: NSTEP and REPEAT must be positive\n");
    return 2;
  }
  m->opt.timestep = 1e-3;
  m->opt.integrator = mjINT_RK4;
  m->opt.disableflags |= mjDSBL_CONTACT | mjDSBL_LIMIT;

  double* q0 = calloc((size_t)m->nq, sizeof(double));
  int n = 0;
  for (char* tok = strtok(argv[4], ","); tok; tok = strtok(NULL, ",")) {
    if (n >= m->nq) {
      n++;
      break;
    }
    q0[n++] = atof(tok);
  }
  if (n != m->nq) {
    fprintf(stderr, "mj_step_loop: MuJoCo sees %d coordinates, q0 has %d\n", m->nq, n);
    return 2;
  }

  mjData* d = mj_makeData(m);
  double seconds[1000];
  for (int r = 0; r < repeat; r++) {
    mj_resetData(m, d);
    memcpy(d->qpos, q0, sizeof(double) * (size_t)m->nq);
    double start = now();
    for (long k = 0; k < nstep; k++) mj_step(m, d);
    seconds[r] = now() - start;
  }
  printf("{\"steps\": %ld, \"mujoco_version\": \"%s\", \"seconds\": [", nstep, mj_versionString());
  for (int r = 0; r < repeat; r++) printf("%s%.9g", r ? ", " : "", seconds[r]);
  qsort(seconds, (size_t)repeat, sizeof(double), cmp);
  double median = repeat % 2 ? seconds[repeat / 2]
                             : 0.5 * (seconds[repeat / 2 - 1] + seconds[repeat / 2]);
  printf("], \"median_s\": %.9g, \"final_q\": [", median);
  for (int i = 0; i < m->nq; i++) printf("%s%.17g", i ? ", " : "", d->qpos[i]);
  printf("]}\n");
  mj_deleteData(d);
  mj_deleteModel(m);
  free(q0);
  return 0;
}
