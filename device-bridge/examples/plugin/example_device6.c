/* An example needlesim device plug-in of the 6-DOF ABI, version 2 (see ../../include/needlesim_device.h):
 * a "device" whose base point moves along a straight line, p(t) = p0 + v t, and whose orientation turns
 * at a constant rate about a fixed world axis, R(t) = rot(axis, th0 + om t) (t from nsd_open); it
 * records the wrenches it is sent.
 * config: space-separated key=value: x0 y0 z0 (m), vx vy vz (m/s), ax ay az (the world rotation axis,
 * default +z; normalised), th0 (rad), om (rad/s), dof=3|6 (what nsd_output_dof reports, default 6),
 * buttons=N (the button mask it reports, default 0), record=PATH (on close, write
 * "fx fy fz tx ty tz writes" of the last wrench to PATH).
 * Build: cc -shared -fPIC -I../../include -o libexample_device6.so example_device6.c
 * (-DEXAMPLE_ABI_VERSION=N makes nsd_abi_version report N instead, to test the bridge's refusal.) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "needlesim_device.h"

#ifndef EXAMPLE_ABI_VERSION
#define EXAMPLE_ABI_VERSION NSD_ABI_VERSION
#endif

typedef struct {
    double p0[3], v[3], axis[3], th0, om, last[6], t0;
    int dof;
    unsigned buttons;
    long writes;
    char record[512], err[128];
} Dev;
static char open_err[128] = "";

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}
int nsd_abi_version(void) { return EXAMPLE_ABI_VERSION; }
void* nsd_open(const char* config) {
    Dev* d = calloc(1, sizeof(Dev));
    char buf[1024], *tok, *save = NULL;
    double n;
    d->axis[2] = 1.0, d->dof = 6;
    snprintf(buf, sizeof buf, "%s", config);
    for (tok = strtok_r(buf, " ", &save); tok; tok = strtok_r(NULL, " ", &save)) {
        if (sscanf(tok, "x0=%lf", &d->p0[0]) || sscanf(tok, "y0=%lf", &d->p0[1]) || sscanf(tok, "z0=%lf", &d->p0[2]) ||
            sscanf(tok, "vx=%lf", &d->v[0]) || sscanf(tok, "vy=%lf", &d->v[1]) || sscanf(tok, "vz=%lf", &d->v[2]) ||
            sscanf(tok, "ax=%lf", &d->axis[0]) || sscanf(tok, "ay=%lf", &d->axis[1]) || sscanf(tok, "az=%lf", &d->axis[2]) ||
            sscanf(tok, "th0=%lf", &d->th0) || sscanf(tok, "om=%lf", &d->om) || sscanf(tok, "dof=%d", &d->dof) ||
            sscanf(tok, "buttons=%u", &d->buttons))
            continue;
        if (strncmp(tok, "record=", 7) == 0) { snprintf(d->record, sizeof d->record, "%s", tok + 7); continue; }
        snprintf(open_err, sizeof open_err, "example device6: bad config entry '%s'", tok);
        free(d);
        return NULL;
    }
    n = sqrt(d->axis[0] * d->axis[0] + d->axis[1] * d->axis[1] + d->axis[2] * d->axis[2]);
    if (!(n > 0)) { snprintf(open_err, sizeof open_err, "example device6: zero rotation axis"); free(d); return NULL; }
    for (int i = 0; i < 3; i++) d->axis[i] /= n;
    d->t0 = now_s();
    return d;
}
int nsd_output_dof(void* dev) { return ((Dev*)dev)->dof; }
int nsd_read_pose6(void* dev, double p[3], double q[4], uint32_t* buttons) {
    Dev* d = dev;
    double t = now_s() - d->t0, th = d->th0 + d->om * t;
    for (int i = 0; i < 3; i++) p[i] = d->p0[i] + d->v[i] * t;
    q[0] = cos(0.5 * th);
    for (int i = 0; i < 3; i++) q[1 + i] = sin(0.5 * th) * d->axis[i];
    *buttons = d->buttons;
    return 0;
}
int nsd_write_wrench(void* dev, const double f[3], const double tq[3]) {
    Dev* d = dev;
    for (int i = 0; i < 3; i++)
        if (f[i] != f[i] || tq[i] != tq[i]) { snprintf(d->err, sizeof d->err, "example device6: NaN wrench"); return 1; }
    memcpy(d->last, f, 3 * sizeof(double));
    memcpy(d->last + 3, tq, 3 * sizeof(double));
    d->writes++;
    return 0;
}
/* Not part of the ABI: lets a test read what the device was last sent. */
long nsd_example_last_wrench(void* dev, double out[6]) {
    Dev* d = dev;
    memcpy(out, d->last, sizeof d->last);
    return d->writes;
}
void nsd_close(void* dev) {
    Dev* d = dev;
    FILE* f = d->record[0] ? fopen(d->record, "w") : NULL;
    if (f) {
        fprintf(f, "%.17g %.17g %.17g %.17g %.17g %.17g %ld\n", d->last[0], d->last[1], d->last[2], d->last[3], d->last[4], d->last[5], d->writes);
        fclose(f);
    }
    free(d);
}
const char* nsd_last_error(void* dev) { return dev ? ((Dev*)dev)->err : open_err; }
