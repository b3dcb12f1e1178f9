//! `main.c` of the exported C: a log of the unit on standard input to the
//! compensated log of `dtg-vib compensate` on standard output, in the
//! unit's column names and units.

/// `main.c`.
pub(super) const MAIN_C: &str = r#"/* Reads a log of the unit (its time column, gyros, accelerometers and any
 * other columns, in its units) on standard input and writes the compensated
 * log of `dtg-vib compensate` on standard output: the time, gyro and
 * accelerometer columns, then the others as given; rows from the first full
 * window on; compensated rates and calibrated accelerations in the log's
 * units. The log is one segment: split a log at its gaps before (as
 * `compensate` does, docs/formats.md "Record of any unit"). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "dtg_model.h"

#define MAX_COLS 256
#define MAX_LINE 65536

static int split(char *line, char **cells) {
    int n = 0;
    char *p = line;
    char *end = line + strlen(line);
    while (end > line && (end[-1] == '\n' || end[-1] == '\r')) *--end = '\0';
    cells[n++] = p;
    for (; *p; p++) {
        if (*p == ',') {
            *p = '\0';
            if (n == MAX_COLS) return -1;
            cells[n++] = p + 1;
        }
    }
    return n;
}

static int find(char **names, int ncols, const char *want) {
    int i;
    for (i = 0; i < ncols; i++)
        if (strcmp(names[i], want) == 0) return i;
    return -1;
}

static void print_row(const double *v, int t, const double *rate, const double *acc,
                      const int *other, int n_other) {
    int k;
    printf("%.17g", v[t]);
    for (k = 0; k < DTG_N_GYROS; k++) printf(",%.17g", rate[k] / DTG_RATE_TO_DEG_H);
    for (k = 0; k < DTG_N_ACCELS; k++) printf(",%.17g", acc[k] / DTG_FORCE_TO_G);
    for (k = 0; k < n_other; k++) printf(",%.17g", v[other[k]]);
    printf("\n");
}

int main(void) {
    static char line[MAX_LINE];
    static char header[MAX_LINE];
    static const char *gyro_names[] = DTG_GYRO_NAMES;
    static const char *accel_names[] = DTG_ACCEL_NAMES;
    static const char *extra_names[] = DTG_EXTRA_NAMES;
    char *cells[MAX_COLS];
    char *names[MAX_COLS];
    int time_col, gyro_col[DTG_N_GYROS], accel_col[DTG_N_ACCELS], extra_col[DTG_N_EXTRA + 1];
    int other[MAX_COLS], n_other = 0;
    int ncols, i, k, row = 1;
    dtg_state s;
    if (!fgets(header, sizeof header, stdin)) {
        fprintf(stderr, "dtg: empty input: expected a log CSV header\n");
        return 2;
    }
    ncols = split(header, names);
    if (ncols < 0) {
        fprintf(stderr, "dtg: more than %d columns\n", MAX_COLS);
        return 2;
    }
    time_col = find(names, ncols, DTG_TIME_NAME);
    if (time_col < 0) {
        fprintf(stderr, "dtg: line 1: no time column '%s'\n", DTG_TIME_NAME);
        return 2;
    }
    for (k = 0; k < DTG_N_GYROS; k++) {
        gyro_col[k] = find(names, ncols, gyro_names[k]);
        if (gyro_col[k] < 0) {
            fprintf(stderr, "dtg: line 1: no gyro column '%s'\n", gyro_names[k]);
            return 2;
        }
    }
    for (k = 0; k < DTG_N_ACCELS; k++) {
        accel_col[k] = find(names, ncols, accel_names[k]);
        if (accel_col[k] < 0) {
            fprintf(stderr, "dtg: line 1: no accelerometer column '%s'\n", accel_names[k]);
            return 2;
        }
    }
    for (k = 0; k < DTG_N_EXTRA; k++) {
        extra_col[k] = find(names, ncols, extra_names[k]);
        if (extra_col[k] < 0) {
            fprintf(stderr, "dtg: line 1: no column '%s' (the model reads it)\n", extra_names[k]);
            return 2;
        }
    }
    for (i = 0; i < ncols; i++) {
        int own = i == time_col;
        for (k = 0; k < DTG_N_GYROS; k++) own |= gyro_col[k] == i;
        for (k = 0; k < DTG_N_ACCELS; k++) own |= accel_col[k] == i;
        if (!own) other[n_other++] = i;
    }
    printf("%s", DTG_TIME_NAME);
    for (k = 0; k < DTG_N_GYROS; k++) printf(",%s", gyro_names[k]);
    for (k = 0; k < DTG_N_ACCELS; k++) printf(",%s", accel_names[k]);
    for (i = 0; i < n_other; i++) printf(",%s", names[other[i]]);
    printf("\n");
    dtg_init(&s);
    /* Outputs lag DTG_LOOKAHEAD rows: pv holds the last ones, oldest first,
     * whose outputs come next. */
    static double v[MAX_COLS], pv[DTG_LOOKAHEAD][MAX_COLS];
    double rate[DTG_N_GYROS], acc_out[DTG_N_ACCELS];
    while (fgets(line, sizeof line, stdin)) {
        double gyro[DTG_N_GYROS], acc[DTG_N_ACCELS], extra[DTG_N_EXTRA + 1];
        row++;
        if (split(line, cells) != ncols) {
            fprintf(stderr, "dtg: line %d: expected %d cells\n", row, ncols);
            return 2;
        }
        for (i = 0; i < ncols; i++) {
            char *end;
            v[i] = strtod(cells[i], &end);
            if (end == cells[i] || *end != '\0') {
                fprintf(stderr, "dtg: line %d, column %d: '%s' is not a number\n", row, i + 1, cells[i]);
                return 2;
            }
        }
        for (k = 0; k < DTG_N_GYROS; k++) gyro[k] = v[gyro_col[k]] * DTG_RATE_TO_DEG_H;
        for (k = 0; k < DTG_N_ACCELS; k++) acc[k] = v[accel_col[k]] * DTG_FORCE_TO_G;
        for (k = 0; k < DTG_N_EXTRA; k++) extra[k] = v[extra_col[k]];
        if (dtg_step(&s, gyro, acc, extra, rate, acc_out))
            print_row(pv[0], time_col, rate, acc_out, other, n_other);
        for (k = 0; k + 1 < DTG_LOOKAHEAD; k++)
            for (i = 0; i < ncols; i++) pv[k][i] = pv[k + 1][i];
        for (i = 0; i < ncols; i++) pv[DTG_LOOKAHEAD - 1][i] = v[i];
    }
    {
        /* Row k of the flush is the k-th of the last DTG_LOOKAHEAD rows. */
        double rates[DTG_LOOKAHEAD][DTG_N_GYROS], accs[DTG_LOOKAHEAD][DTG_N_ACCELS];
        int got = dtg_flush(&s, rates, accs);
        for (k = 0; k < DTG_LOOKAHEAD; k++)
            if (got & (1 << k)) print_row(pv[k], time_col, rates[k], accs[k], other, n_other);
    }
    return 0;
}
"#;
