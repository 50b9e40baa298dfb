/* An example needlesim device plug-in of the 2D ABI, version 1 (see ../../include/needlesim_device.h; the
 * 6-DOF example is example_device6.c): a "device" whose pose moves
 * along a straight line over time, q(t) = q0 + v t (t from nsd_open), which records the forces it is sent.
 * config: space-separated key=value: x0 y0 th0 (m, rad), vx vy om (m/s, rad/s),
 * record=PATH (on close, write "fx fy tau writes" of the last force to PATH), fail=1 (nsd_open fails).
 * Build: cc -shared -fPIC -I../../include -o libexample_device.so example_device.c */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "needlesim_device.h"

typedef struct {
    double q0[3], v[3], last[3], t0;
    long writes;
    char record[512], err[128];
} Dev;
static char open_err[128] = "";

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}
int nsd_abi_version(void) { return NSD_ABI_VERSION_PLANAR; }
void* nsd_open(const char* config) {
    Dev* d = calloc(1, sizeof(Dev));
    char buf[1024], *tok, *save = NULL;
    snprintf(buf, sizeof buf, "%s", config);
    for (tok = strtok_r(buf, " ", &save); tok; tok = strtok_r(NULL, " ", &save)) {
        if (sscanf(tok, "x0=%lf", &d->q0[0]) || sscanf(tok, "y0=%lf", &d->q0[1]) || sscanf(tok, "th0=%lf", &d->q0[2]) ||
            sscanf(tok, "vx=%lf", &d->v[0]) || sscanf(tok, "vy=%lf", &d->v[1]) || sscanf(tok, "om=%lf", &d->v[2]))
            continue;
        if (strncmp(tok, "record=", 7) == 0) { snprintf(d->record, sizeof d->record, "%s", tok + 7); continue; }
        snprintf(open_err, sizeof open_err, "example device: bad config entry '%s'", tok);
        free(d);
        return NULL;
    }
    d->t0 = now_s();
    return d;
}
int nsd_read_pose(void* dev, double* x, double* y, double* th, uint32_t* buttons) {
    Dev* d = dev;
    double t = now_s() - d->t0;
    *x = d->q0[0] + d->v[0] * t, *y = d->q0[1] + d->v[1] * t, *th = d->q0[2] + d->v[2] * t, *buttons = 1;
    return 0;
}
int nsd_write_force(void* dev, double fx, double fy, double tau) {
    Dev* d = dev;
    if (fx != fx || fy != fy || tau != tau) { snprintf(d->err, sizeof d->err, "example device: NaN force"); return 1; }
    d->last[0] = fx, d->last[1] = fy, d->last[2] = tau, d->writes++;
    return 0;
}
/* Not part of the ABI: lets a test read what the device was last sent. */
long nsd_example_last_force(void* dev, double out[3]) {
    Dev* d = dev;
    memcpy(out, d->last, sizeof d->last);
    return d->writes;
}
void nsd_close(void* dev) {
    Dev* d = dev;
    FILE* f = d->record[0] ? fopen(d->record, "w") : NULL;
    if (f) { fprintf(f, "%.17g %.17g %.17g %ld\n", d->last[0], d->last[1], d->last[2], d->writes); fclose(f); }
    free(d);
}
const char* nsd_last_error(void* dev) { return dev ? ((Dev*)dev)->err : open_err; }
