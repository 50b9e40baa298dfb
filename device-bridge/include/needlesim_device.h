/*
 * needlesim_device.h — the C ABI of a needlesim-bridge device plug-in (ABI version 2; version 1, the
 * 2D ABI, is still loaded).
 *
 * A plug-in is a shared library (.so). needlesim-bridge loads it (`--device plugin --plugin LIB.so
 * --plugin-config STR`), calls nsd_abi_version() and then looks up the functions of that version:
 *   ABI 2 (NSD_ABI_VERSION, 6-DOF):  nsd_open, nsd_output_dof, nsd_read_pose6, nsd_write_wrench,
 *                                    nsd_close, nsd_last_error;
 *   ABI 1 (NSD_ABI_VERSION_PLANAR, 2D): nsd_open, nsd_read_pose, nsd_write_force, nsd_close,
 *                                    nsd_last_error — driven through the planar mapping below.
 * Any other version is refused ("unknown ABI version N"), as is a library missing a function of its
 * version (the message names it). Then nsd_open(config) once (and, ABI 2, nsd_output_dof(dev)), and
 * then, every device period (1 kHz by default), from one thread only:
 *     read the pose          -> sent to the simulation server,
 *     write the force/torque -> what the bridge rendered (already limited, and ramped to zero by its
 *                               watchdog when the server goes away).
 * On exit (normal, error or Ctrl-C) the bridge always writes a zero force and torque before
 * nsd_close(dev). Calls never overlap; nsd_close is the last call on a handle.
 *
 * Units and frames (ABI 2). One right-handed world frame, fixed to the device's base, in metres:
 *  - position_m[3]: the base point of the needle (the point the hand holds, where force is applied),
 *    world frame, m;
 *  - orientation_wxyz[4]: a unit quaternion (w, x, y, z), Hamilton convention, rotating the needle's
 *    body frame into the world frame (in the body frame the shaft runs along +x, base to tip). The
 *    bridge normalises it; a zero or non-finite quaternion is an error;
 *  - force_n[3]: the force to apply at the base point, world frame, N;
 *  - torque_nm[3]: the torque to apply about the base point, world frame, N·m (a force-only device,
 *    nsd_output_dof = 3, is always sent 0 and may ignore it).
 * Put any mapping from the device's own frame (axes, scale, offset, workspace centre) in the plug-in,
 * configured by the config string.
 *
 * The planar mapping (ABI 1, and a 2D session): a 2D pose (x, y, theta) is the 6-DOF pose with
 * position (x, y, 0) and orientation a rotation theta about +z, (cos theta/2, 0, 0, sin theta/2);
 * a 2D device is sent the planar part (fx, fy, torque about z) of the wrench. Units: metres,
 * radians (counter-clockwise > 0), newtons, newton-metres.
 *
 * Return codes: 0 = ok, nonzero = error; then nsd_last_error(dev) gives a message (a NUL-terminated
 * string owned by the plug-in, valid until the next call on that handle). nsd_open returns NULL on
 * failure; nsd_last_error(NULL) then describes why. A failed read or write stops the bridge (after
 * it has tried to write a zero force).
 *
 * Wrapping a vendor SDK (~50 lines):
 *  - OpenHaptics (HD API, e.g. Geomagic Touch: 6-DOF pose, 3-DOF force → nsd_output_dof = 3):
 *    nsd_open: hdInitDevice(config or HD_DEFAULT_DEVICE), hdEnable(HD_FORCE_OUTPUT), hdStartScheduler();
 *    nsd_read_pose6: hdBeginFrame, hdGetDoublev(HD_CURRENT_POSITION) (mm → m) and
 *    HD_CURRENT_TRANSFORM (rotation block → quaternion), hdGetIntegerv(HD_CURRENT_BUTTONS);
 *    nsd_write_wrench: hdSetDoublev(HD_CURRENT_FORCE, force_n) (and HD_CURRENT_TORQUE on 6-DOF-output
 *    models), then hdEndFrame; nsd_close: hdStopScheduler, hdDisableDevice. Map hdGetError() to
 *    nsd_last_error. (Either call the frame functions directly from the bridge's thread, or exchange
 *    with your own servo callback through a mutex-free double buffer.)
 *  - Force Dimension (DHD/DRD): nsd_open: dhdOpen() / dhdOpenID(atoi(config)), dhdEnableForce(DHD_ON);
 *    nsd_read_pose6: dhdGetPosition(&x,&y,&z) + dhdGetOrientationFrame(R) → quaternion,
 *    dhdGetButtonMask(); nsd_write_wrench: dhdSetForceAndTorque(fx, fy, fz, tx, ty, tz);
 *    nsd_close: dhdClose(); dhdErrorGetLastStr() → nsd_last_error.
 *  - CHAI3D: nsd_open: cHapticDeviceHandler h; h.getDevice(dev, index); dev->open(); nsd_read_pose6:
 *    dev->getPosition(p), dev->getRotation(R) → quaternion, dev->getUserSwitches(mask);
 *    nsd_write_wrench: dev->setForceAndTorque(cVector3d(f), cVector3d(t)); nsd_close: dev->close().
 *    (Compile as C++ with the functions below inside extern "C".)
 */
#ifndef NEEDLESIM_DEVICE_H
#define NEEDLESIM_DEVICE_H

#include <stdint.h>

/* The 6-DOF ABI. */
#define NSD_ABI_VERSION 2
/* The 2D ABI of earlier releases, still loaded (through the planar mapping). */
#define NSD_ABI_VERSION_PLANAR 1

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Both versions ---------------------------------------------------------------------------- */

/* The version of this header the plug-in was built against: NSD_ABI_VERSION (2), or
 * NSD_ABI_VERSION_PLANAR (1) for a 2D plug-in. */
int nsd_abi_version(void);
/* Open the device; config is the bridge's --plugin-config string (never NULL, maybe ""). NULL on failure. */
void* nsd_open(const char* config);
/* Stop forces and release the device. dev is not used afterwards. */
void nsd_close(void* dev);
/* The message of the last failed call on dev (of the last failed nsd_open if dev is NULL). */
const char* nsd_last_error(void* dev);

/* ---- ABI 2: 6-DOF ----------------------------------------------------------------------------- */

/* What the device renders: 3 = force only (the bridge renders with the force–position block of the
 * server's stiffness and always sends a zero torque), 6 = force and torque. Called once after nsd_open;
 * any other value is refused. */
int nsd_output_dof(void* dev);
/* The current pose (see "Units and frames"): position_m[3] (m, world), orientation_wxyz[4] (unit
 * quaternion, body → world); buttons: a bit per button (1 = pressed). Button 0 (bit 1): each press
 * turns the needle 180° about its axis (flips a bevel tip). */
int nsd_read_pose6(void* dev, double position_m[3], double orientation_wxyz[4], uint32_t* buttons);
/* Command this force (N, world, at the base point) and torque (N·m, world, about the base point)
 * until the next call. */
int nsd_write_wrench(void* dev, const double force_n[3], const double torque_nm[3]);

/* ---- ABI 1: 2D (the simulation's plane; see "The planar mapping") --------------------------- */

/* The current pose of the device in the simulation plane (m, m, rad); buttons as for nsd_read_pose6. */
int nsd_read_pose(void* dev, double* x_m, double* y_m, double* theta_rad, uint32_t* buttons);
/* Command this in-plane force (N) and torque about the plane's normal (N·m) until the next call. */
int nsd_write_force(void* dev, double fx_n, double fy_n, double torque_nm);

#ifdef __cplusplus
}
#endif

#endif
