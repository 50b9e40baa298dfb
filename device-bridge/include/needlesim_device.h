/*
 * needlesim_device.h — the C ABI of a needlesim-bridge device plug-in (ABI version 1).
 *
 * A plug-in is a shared library (.so) exporting the five functions below plus nsd_last_error.
 * needlesim-bridge loads it (`--device plugin --plugin LIB.so --plugin-config STR`), calls
 * nsd_abi_version() and refuses a library that does not return NSD_ABI_VERSION, then nsd_open(config)
 * once, and then, every device period (1 kHz by default), from one thread only:
 *     nsd_read_pose(dev, ...)   -> the pose is sent to the simulation server,
 *     nsd_write_force(dev, ...) -> the force/torque the bridge rendered (already limited and
 *                                  ramped to zero by its watchdog when the server goes away).
 * On exit (normal, error or Ctrl-C) the bridge always calls nsd_write_force(dev, 0, 0, 0) before
 * nsd_close(dev). Calls never overlap; nsd_close is the last call on a handle.
 *
 * Units and frame: the simulation's plane, metres and radians; force in newtons on the
 * needle base (the hand), torque in newton-metres about the plane's normal (counter-clockwise > 0).
 * Return codes: 0 = ok, nonzero = error; then nsd_last_error(dev) gives a message (a NUL-terminated
 * string owned by the plug-in, valid until the next call on that handle). nsd_open returns NULL on
 * failure; nsd_last_error(NULL) then describes why. A failed read or write stops the bridge (after
 * it has tried to write a zero force).
 *
 * Wrapping a vendor SDK (~50 lines):
 *  - OpenHaptics (HD API): nsd_open: hdInitDevice(config or HD_DEFAULT_DEVICE), hdEnable(HD_FORCE_OUTPUT),
 *    hdStartScheduler(); keep the device handle in your struct. nsd_read_pose: hdBeginFrame,
 *    hdGetDoublev(HD_CURRENT_POSITION) (mm → m) and HD_CURRENT_TRANSFORM (project the stylus axis on the
 *    plane → theta), hdGetIntegerv(HD_CURRENT_BUTTONS); nsd_write_force: hdSetDoublev(HD_CURRENT_FORCE,
 *    {fx, fy, 0}) and, on 6-DOF-output models, HD_CURRENT_TORQUE, then hdEndFrame; nsd_close:
 *    hdStopScheduler, hdDisableDevice. Map hdGetError() to nsd_last_error. (Either call the frame
 *    functions directly from the bridge's thread, or exchange with your own servo callback through a
 *    mutex-free double buffer.)
 *  - Force Dimension (DHD/DRD): nsd_open: dhdOpen() / dhdOpenID(atoi(config)), dhdEnableForce(DHD_ON);
 *    nsd_read_pose: dhdGetPosition(&x,&y,&z) + dhdGetOrientationRad or the gripper angle → theta,
 *    dhdGetButtonMask(); nsd_write_force: dhdSetForceAndTorque(fx, fy, 0, 0, 0, tau);
 *    nsd_close: dhdClose(); dhdErrorGetLastStr() → nsd_last_error.
 *  - CHAI3D: nsd_open: cHapticDeviceHandler h; h.getDevice(dev, index); dev->open(); nsd_read_pose:
 *    dev->getPosition(p), dev->getRotation(R) → theta, dev->getUserSwitches(mask); nsd_write_force:
 *    dev->setForceAndTorque(cVector3d(fx,fy,0), cVector3d(0,0,tau)); nsd_close: dev->close().
 *    (Compile as C++ with the functions below inside extern "C".)
 * A plane mapping (which device axes are x and y, a scale, an offset) belongs in the config string.
 */
#ifndef NEEDLESIM_DEVICE_H
#define NEEDLESIM_DEVICE_H

#include <stdint.h>

#define NSD_ABI_VERSION 1

#ifdef __cplusplus
extern "C" {
#endif

/* Must return NSD_ABI_VERSION (the version of this header the plug-in was built against). */
int nsd_abi_version(void);
/* Open the device; config is the bridge's --plugin-config string (never NULL, maybe ""). NULL on failure. */
void* nsd_open(const char* config);
/* The current pose of the device in the simulation plane; buttons: a bit per button (1 = pressed).
 * Button 0 (bit 1): each press turns the needle 180° about its axis (flips a bevel tip). */
int nsd_read_pose(void* dev, double* x_m, double* y_m, double* theta_rad, uint32_t* buttons);
/* Command this force (N) and torque (N·m) until the next call. */
int nsd_write_force(void* dev, double fx_n, double fy_n, double torque_nm);
/* Stop forces and release the device. dev is not used afterwards. */
void nsd_close(void* dev);
/* The message of the last failed call on dev (of the last failed nsd_open if dev is NULL). */
const char* nsd_last_error(void* dev);

#ifdef __cplusplus
}
#endif

#endif
