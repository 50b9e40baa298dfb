//! Haptic devices behind one trait: a scripted trajectory, a simulated operator's hand on a device,
//! and real devices through a C plug-in (`include/needlesim_device.h`, ABI 2 for 6-DOF devices,
//! ABI 1 for 2D ones).
//!
//! Every device speaks 6-DOF (poses [`Pose6`], wrenches `(Fx, Fy, Fz, τx, τy, τz)` in N and N·m,
//! world frame; the conventions of `needlesim_channel::spatial`). A 2D device (a 2D trajectory,
//! an ABI 1 plug-in) is the same path restricted to the plane: its pose `(x, y, θ)` is embedded as
//! `(x, y, 0)` and a rotation θ about +z, and it is sent the planar part `(Fx, Fy, τz)` of the wrench.

use std::ffi::{CStr, CString, c_char, c_int, c_void};
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, anyhow, bail};
use needlesim_channel::spatial::{quat_exp, quat_mul, quat_normalize, wrench_to_planar};

use crate::render::{DeviceOutput, Pose6};

/// What a device reports each period.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DeviceState {
    pub pose: Pose6,
    /// A bit per button, 1 = pressed.
    pub buttons: u32,
}

/// A haptic device, driven from one thread at the device rate.
pub trait Device {
    fn name(&self) -> &str;
    /// The pose at `t_s` seconds since the loop started (devices with their own clock may ignore it).
    fn read_pose(&mut self, t_s: f64) -> Result<DeviceState>;
    /// Command this wrench `(Fx, Fy, Fz, τx, τy, τz)` (N, N·m, world) until the next call; a
    /// device renders the components it can (a 2D device the planar ones, a force-only one the force).
    fn write_force(&mut self, wrench: [f64; 6]) -> Result<()>;
    /// What the device renders (the axes the safety layer works on).
    fn output(&self) -> DeviceOutput {
        DeviceOutput::Wrench
    }
    /// Release the device (idempotent). The bridge writes a zero force before.
    fn close(&mut self);
}

// ---------------------------------------------------------------------------------------------
// Trajectory

/// A trajectory CSV, linearly interpolated (orientations by slerp), optionally replayed in a
/// loop: the 2D `t_s,x_m,y_m,theta_rad` or the 3D `t_s,x_m,y_m,z_m,qw,qx,qy,qz` (both parsed by
/// needlesim-trajectory, chosen by the header line), either with an optional last column
/// `buttons` (the button mask, an unsigned integer, held from its row until the next: a step, not
/// interpolated).
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    inner: Inner,
    /// `(t_s, buttons)` per row when the CSV has the `buttons` column, else empty.
    buttons: Vec<(f64, u32)>,
    /// Replay from the start after the end (else hold the last pose).
    pub looped: bool,
}

#[derive(Debug, Clone, PartialEq)]
enum Inner {
    Planar(needlesim_trajectory::Trajectory),
    Spatial(needlesim_trajectory::Trajectory3),
}

impl Trajectory {
    /// Reads a CSV file by the one rule for local files (a regular file, not a link, at most
    /// [`needlesim_localfile::MAX_LOCAL_FILE_BYTES`], opened without blocking: a FIFO or a device
    /// is refused, not waited on); errors name the file and the line.
    pub fn load(path: impl AsRef<Path>, looped: bool) -> Result<Self> {
        let path = path.as_ref();
        let text = needlesim_localfile::read_local_file(path, needlesim_localfile::MAX_LOCAL_FILE_BYTES)
            .map_err(|e| anyhow::anyhow!("{}", e.named("trajectory")))?;
        Self::parse(&text, &path.display().to_string(), looped)
    }

    /// Parses CSV text; `name` leads error messages (`name: trajectory line N: …`). The first line
    /// that is neither blank nor a `#` comment decides: a header starting `t_s,x_m,y_m,z_m` is the
    /// 3D form, anything else is read as the 2D form (whose errors then say what it expected).
    pub fn parse(text: &str, name: &str, looped: bool) -> Result<Self> {
        let header = text.lines().map(str::trim).find(|l| !l.is_empty() && !l.starts_with('#')).unwrap_or("");
        let compact: String = header.chars().filter(|c| !c.is_whitespace()).collect();
        let (poses, buttons) = if compact.ends_with(",buttons") { split_buttons(text, name)? } else { (text.to_owned(), vec![]) };
        let inner = if compact.starts_with("t_s,x_m,y_m,z_m") {
            Inner::Spatial(needlesim_trajectory::Trajectory3::parse_csv(&poses).map_err(|e| anyhow!("{name}: {e}"))?)
        } else {
            Inner::Planar(needlesim_trajectory::Trajectory::parse_csv(&poses).map_err(|e| anyhow!("{name}: {e}"))?)
        };
        Ok(Self { inner, buttons, looped })
    }

    /// The button mask at `t_s` (the last row at or before it; the first row's before the start; 0
    /// without a `buttons` column).
    pub fn buttons_at(&self, t_s: f64) -> u32 {
        let t = self.wrap(t_s);
        let k = self.buttons.partition_point(|(tr, _)| *tr <= t);
        self.buttons.get(k.saturating_sub(1)).map_or(0, |b| b.1)
    }

    /// `t_s` mapped into the trajectory's span when looped.
    fn wrap(&self, t_s: f64) -> f64 {
        let (t0, d) = (self.span_s().0, self.duration_s());
        if self.looped && d > 0.0 && t_s > t0 + d { t0 + (t_s - t0).rem_euclid(d) } else { t_s }
    }

    /// True for a 3D trajectory.
    pub fn is_spatial(&self) -> bool {
        matches!(self.inner, Inner::Spatial(_))
    }

    fn span_s(&self) -> (f64, f64) {
        match &self.inner {
            Inner::Planar(t) => t.span_s(),
            Inner::Spatial(t) => t.span_s(),
        }
    }

    /// Duration from the first to the last row (s).
    pub fn duration_s(&self) -> f64 {
        let (t0, t1) = self.span_s();
        t1 - t0
    }

    /// Pose and velocity (slope of the segment: linear, m/s, and angular, rad/s, world frame) at
    /// time `t_s` (before the start: the first pose, at rest).
    pub fn sample(&self, t_s: f64) -> (Pose6, [f64; 6]) {
        let t = self.wrap(t_s);
        match &self.inner {
            Inner::Planar(tr) => {
                let (q, v) = tr.pose_and_velocity_at(t);
                (Pose6::planar([q.x_m, q.y_m, q.theta_rad]), [v.x_m, v.y_m, 0.0, 0.0, 0.0, v.theta_rad])
            }
            Inner::Spatial(tr) => {
                let (q, v, w) = tr.pose_and_velocity_at(t);
                (Pose6 { position_m: q.position_m, orientation: q.quat_wxyz }, [v[0], v[1], v[2], w[0], w[1], w[2]])
            }
        }
    }
}

/// Splits the last column, `buttons`, off a trajectory CSV: (the CSV without it, `(t_s, buttons)`
/// per data row). Blank and `#` lines are kept as they are (so line numbers in the pose parser's
/// errors stay right); a row's t_s is its first field (the pose parser checks it), its buttons an
/// unsigned integer (else an error naming the line).
fn split_buttons(text: &str, name: &str) -> Result<(String, Vec<(f64, u32)>)> {
    let mut out = String::with_capacity(text.len());
    let mut buttons = Vec::new();
    let mut header_seen = false;
    for (i, line) in text.lines().enumerate() {
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') {
            out.push_str(line);
        } else {
            let (rest, last) = line.rsplit_once(',').ok_or_else(|| anyhow!("{name}: trajectory line {}: no buttons column", i + 1))?;
            out.push_str(rest);
            if header_seen {
                let b = last.trim().parse::<u32>().map_err(|_| {
                    anyhow!("{name}: trajectory line {}: column buttons: `{}` is not an unsigned integer", i + 1, last.trim())
                })?;
                let t_s = rest.split(',').next().and_then(|v| v.trim().parse::<f64>().ok()).unwrap_or(f64::NAN);
                buttons.push((t_s, b));
            }
            header_seen = true;
        }
        out.push('\n');
    }
    Ok((out, buttons))
}

// ---------------------------------------------------------------------------------------------
// Scripted

/// Replays a trajectory; forces are recorded but move nothing.
#[derive(Debug, Clone)]
pub struct ScriptedDevice {
    traj: Trajectory,
    /// The last wrench written.
    pub last_force: [f64; 6],
    /// How many wrenches were written.
    pub force_writes: u64,
    /// The largest |F| written.
    pub max_force_n: f64,
}

impl ScriptedDevice {
    pub fn new(traj: Trajectory) -> Self {
        Self { traj, last_force: [0.0; 6], force_writes: 0, max_force_n: 0.0 }
    }
}

impl Device for ScriptedDevice {
    fn name(&self) -> &str {
        "scripted"
    }
    fn read_pose(&mut self, t_s: f64) -> Result<DeviceState> {
        let (pose, _) = self.traj.sample(t_s);
        Ok(DeviceState { pose, buttons: self.traj.buttons_at(t_s) })
    }
    fn write_force(&mut self, wrench: [f64; 6]) -> Result<()> {
        self.last_force = wrench;
        self.force_writes += 1;
        self.max_force_n = self.max_force_n.max(force_norm(&wrench));
        Ok(())
    }
    fn close(&mut self) {}
}

/// |F| of a wrench (N).
pub fn force_norm(w: &[f64; 6]) -> f64 {
    (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt()
}

// ---------------------------------------------------------------------------------------------
// Virtual operator

/// The simulated hand + device, a spring–damper following the trajectory on each of the six axes
/// (x, y, z translational; rotations about x, y, z in world):
/// `m·a = kp e + kd (v_ref − v) + w_rendered − b·v`, with `e = δ(q_ref, q)` the pose error
/// (translation, m, and world rotation vector, rad: `needlesim_channel::spatial::pose_delta`) and
/// `v` the linear and angular velocity (world), integrated by semi-implicit Euler once per
/// `read_pose` with Δt the time since the previous call: `v ← v + Δt·a`, then `p ← p + Δt·v_lin`,
/// `R ← exp(Δt·ω̂) R`. On a 2D trajectory only the planar axes ever move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OperatorParams {
    /// Mass (kg) on x, y, z; rotational inertia (kg·m²) about x, y, z.
    pub mass: [f64; 6],
    /// Damping: N·s/m on x, y, z; N·m·s/rad about x, y, z.
    pub damping: [f64; 6],
    /// PD proportional gains: N/m; N·m/rad.
    pub kp: [f64; 6],
    /// PD derivative gains: N·s/m; N·m·s/rad.
    pub kd: [f64; 6],
}

impl Default for OperatorParams {
    fn default() -> Self {
        // A hand holding a desktop device: 0.3 kg, a 300 N/m grip, critically damped-ish.
        let ax = |t: f64, r: f64| [t, t, t, r, r, r];
        Self { mass: ax(0.3, 1e-4), damping: ax(2.0, 1e-3), kp: ax(300.0, 0.3), kd: ax(15.0, 0.01) }
    }
}

/// The virtual operator's state.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct OperatorState {
    pub t_s: f64,
    pub q: Pose6,
    /// Linear (m/s) and angular (rad/s) velocity, world.
    pub v: [f64; 6],
    /// The wrench last rendered on it.
    pub rendered: [f64; 6],
    /// The PD wrench of the last step.
    pub pd: [f64; 6],
}

#[derive(Debug, Clone)]
pub struct VirtualOperator {
    traj: Trajectory,
    params: OperatorParams,
    state: OperatorState,
    started: bool,
}

impl VirtualOperator {
    /// Starts at rest at the trajectory's first pose.
    pub fn new(traj: Trajectory, params: OperatorParams) -> Self {
        let (q, _) = traj.sample(f64::NEG_INFINITY);
        Self { traj, params, state: OperatorState { q, ..Default::default() }, started: false }
    }
    pub fn state(&self) -> &OperatorState {
        &self.state
    }
    pub fn params(&self) -> &OperatorParams {
        &self.params
    }
}

impl Device for VirtualOperator {
    fn name(&self) -> &str {
        "virtual"
    }
    fn read_pose(&mut self, t_s: f64) -> Result<DeviceState> {
        let s = &mut self.state;
        if !self.started {
            self.started = true;
            s.t_s = t_s;
        }
        let dt = t_s - s.t_s;
        if dt > 0.0 {
            let (q_ref, v_ref) = self.traj.sample(t_s);
            let e = q_ref.delta_from(&s.q);
            let p = &self.params;
            for i in 0..6 {
                s.pd[i] = p.kp[i] * e[i] + p.kd[i] * (v_ref[i] - s.v[i]);
                let a = (s.pd[i] + s.rendered[i] - p.damping[i] * s.v[i]) / p.mass[i];
                s.v[i] += dt * a;
            }
            for i in 0..3 {
                s.q.position_m[i] += dt * s.v[i];
            }
            let turn = quat_exp([dt * s.v[3], dt * s.v[4], dt * s.v[5]]);
            s.q.orientation = quat_normalize(quat_mul(turn, s.q.orientation)).unwrap_or(s.q.orientation);
            s.t_s = t_s;
        }
        if !s.q.position_m.iter().chain(&s.q.orientation).chain(&s.v).all(|x| x.is_finite()) {
            bail!("virtual operator diverged at t = {t_s} s (q = {:?}, v = {:?})", s.q, s.v);
        }
        Ok(DeviceState { pose: s.q, buttons: self.traj.buttons_at(t_s) })
    }
    fn write_force(&mut self, wrench: [f64; 6]) -> Result<()> {
        self.state.rendered = wrench;
        Ok(())
    }
    fn close(&mut self) {}
}

// ---------------------------------------------------------------------------------------------
// Plug-in

/// The ABI version this bridge speaks natively (`NSD_ABI_VERSION` in `include/needlesim_device.h`):
/// 6-DOF pose in, force and optional torque out.
pub const PLUGIN_ABI_VERSION: c_int = 2;
/// The 2D ABI (`NSD_ABI_VERSION_PLANAR`), still loaded and driven through the planar mapping.
pub const PLUGIN_ABI_VERSION_PLANAR: c_int = 1;

type AbiVersionFn = unsafe extern "C" fn() -> c_int;
type OpenFn = unsafe extern "C" fn(*const c_char) -> *mut c_void;
type CloseFn = unsafe extern "C" fn(*mut c_void);
type LastErrorFn = unsafe extern "C" fn(*mut c_void) -> *const c_char;
type ReadPoseFn = unsafe extern "C" fn(*mut c_void, *mut f64, *mut f64, *mut f64, *mut u32) -> c_int;
type WriteForceFn = unsafe extern "C" fn(*mut c_void, f64, f64, f64) -> c_int;
type ReadPose6Fn = unsafe extern "C" fn(*mut c_void, *mut f64, *mut f64, *mut u32) -> c_int;
type WriteWrenchFn = unsafe extern "C" fn(*mut c_void, *const f64, *const f64) -> c_int;
type OutputDofFn = unsafe extern "C" fn(*mut c_void) -> c_int;

/// The entry points of one ABI version.
#[derive(Clone, Copy)]
enum Abi {
    /// ABI 1: the planar pose `(x, y, θ)` and wrench `(Fx, Fy, τ)`.
    Planar { read_pose: ReadPoseFn, write_force: WriteForceFn },
    /// ABI 2: 6-DOF pose, force and torque (a force-only device ignores the torque).
    Spatial { read_pose6: ReadPose6Fn, write_wrench: WriteWrenchFn },
}

/// A device in a shared library implementing `include/needlesim_device.h` (ABI 2, or the 2D ABI 1).
pub struct PluginDevice {
    path: PathBuf,
    name: String,
    dev: *mut c_void,
    abi: Abi,
    output: DeviceOutput,
    close: CloseFn,
    last_error: LastErrorFn,
    // Last field: dropped (dlclose) after everything that points into it.
    lib: libloading::Library,
}

impl PluginDevice {
    /// Loads `path`, checks `nsd_abi_version()` (2, or 1 for a 2D plug-in; any other version is
    /// refused naming it), looks up that version's functions, calls `nsd_open(config)` and, for
    /// ABI 2, `nsd_output_dof(dev)` (3: force only, 6: force and torque; anything else is refused).
    pub fn open(path: impl AsRef<Path>, config: &str) -> Result<Self> {
        let path = path.as_ref().to_path_buf();
        let p = path.display().to_string();
        // SAFETY: loading a library runs its initialisers; the user chose to trust this plug-in.
        let lib = unsafe { libloading::Library::new(&path) }.with_context(|| format!("plug-in {p}: cannot load"))?;
        let sym = |name: &str| format!("plug-in {p}: missing symbol {name} (see include/needlesim_device.h)");
        // SAFETY: the types are those of the header; a library exporting these names with other
        // signatures breaks the plug-in contract.
        let abi_version = unsafe { *lib.get::<AbiVersionFn>(b"nsd_abi_version\0").with_context(|| sym("nsd_abi_version"))? };
        // SAFETY: plug-in calls per the ABI.
        let version = unsafe { abi_version() };
        // SAFETY: as above.
        let (abi, output_dof, open, close, last_error) = unsafe {
            let abi = match version {
                PLUGIN_ABI_VERSION => Abi::Spatial {
                    read_pose6: *lib.get::<ReadPose6Fn>(b"nsd_read_pose6\0").with_context(|| sym("nsd_read_pose6"))?,
                    write_wrench: *lib.get::<WriteWrenchFn>(b"nsd_write_wrench\0").with_context(|| sym("nsd_write_wrench"))?,
                },
                PLUGIN_ABI_VERSION_PLANAR => Abi::Planar {
                    read_pose: *lib.get::<ReadPoseFn>(b"nsd_read_pose\0").with_context(|| sym("nsd_read_pose"))?,
                    write_force: *lib.get::<WriteForceFn>(b"nsd_write_force\0").with_context(|| sym("nsd_write_force"))?,
                },
                other => bail!(
                    "plug-in {p}: unknown ABI version {other} (nsd_abi_version); this bridge loads ABI {PLUGIN_ABI_VERSION} (6-DOF) and ABI {PLUGIN_ABI_VERSION_PLANAR} (2D)"
                ),
            };
            let output_dof = match abi {
                Abi::Spatial { .. } => Some(*lib.get::<OutputDofFn>(b"nsd_output_dof\0").with_context(|| sym("nsd_output_dof"))?),
                Abi::Planar { .. } => None,
            };
            (
                abi,
                output_dof,
                *lib.get::<OpenFn>(b"nsd_open\0").with_context(|| sym("nsd_open"))?,
                *lib.get::<CloseFn>(b"nsd_close\0").with_context(|| sym("nsd_close"))?,
                *lib.get::<LastErrorFn>(b"nsd_last_error\0").with_context(|| sym("nsd_last_error"))?,
            )
        };
        let c = CString::new(config).map_err(|_| anyhow!("plug-in {p}: the config string contains a NUL byte"))?;
        // SAFETY: a valid NUL-terminated string that outlives the call.
        let dev = unsafe { open(c.as_ptr()) };
        if dev.is_null() {
            // SAFETY: nsd_last_error(NULL) is defined by the ABI.
            let msg = unsafe { error_string(last_error(std::ptr::null_mut())) };
            bail!("plug-in {p}: nsd_open failed: {msg}");
        }
        let output = match output_dof {
            // SAFETY: dev is open.
            Some(f) => match unsafe { f(dev) } {
                3 => DeviceOutput::ForceOnly,
                6 => DeviceOutput::Wrench,
                other => {
                    // SAFETY: dev is open and not used afterwards.
                    unsafe { close(dev) };
                    bail!("plug-in {p}: nsd_output_dof returned {other}, expected 3 (force only) or 6 (force and torque)");
                }
            },
            None => DeviceOutput::Wrench,
        };
        let name = format!("plugin:{}", path.file_name().map_or(p.clone(), |f| f.to_string_lossy().into_owned()));
        Ok(Self { path, name, dev, abi, output, close, last_error, lib })
    }

    /// The ABI version the plug-in reported (1 or 2).
    pub fn abi_version(&self) -> c_int {
        match self.abi {
            Abi::Planar { .. } => PLUGIN_ABI_VERSION_PLANAR,
            Abi::Spatial { .. } => PLUGIN_ABI_VERSION,
        }
    }

    /// The device handle (for extra, plug-in specific exports such as the example's `nsd_example_last_force`).
    pub fn handle(&self) -> *mut c_void {
        self.dev
    }

    /// The loaded library (to look up extra exports).
    pub fn library(&self) -> &libloading::Library {
        &self.lib
    }

    fn error(&self, call: &str, code: c_int) -> anyhow::Error {
        // SAFETY: dev is open; the returned string is valid until the next call on it.
        let msg = unsafe { error_string((self.last_error)(self.dev)) };
        anyhow!("plug-in {}: {call} returned {code}: {msg}", self.path.display())
    }
}

/// # Safety
/// `s` is NULL or a valid NUL-terminated string.
unsafe fn error_string(s: *const c_char) -> String {
    if s.is_null() {
        return "(no message)".into();
    }
    // SAFETY: per the function contract.
    let m = unsafe { CStr::from_ptr(s) }.to_string_lossy().into_owned();
    if m.is_empty() { "(no message)".into() } else { m }
}

impl Device for PluginDevice {
    fn name(&self) -> &str {
        &self.name
    }
    fn read_pose(&mut self, _t_s: f64) -> Result<DeviceState> {
        if self.dev.is_null() {
            bail!("plug-in {}: read after close", self.path.display());
        }
        let mut buttons = 0u32;
        let (code, call, pose) = match self.abi {
            Abi::Planar { read_pose, .. } => {
                let mut q = [0.0f64; 3];
                let [x, y, th] = &mut q;
                // SAFETY: dev is open; the out-pointers are valid for the call.
                let code = unsafe { read_pose(self.dev, x, y, th, &mut buttons) };
                (code, "nsd_read_pose", Pose6::planar(q))
            }
            Abi::Spatial { read_pose6, .. } => {
                let mut pose = Pose6::default();
                // SAFETY: dev is open; 3 and 4 doubles, and the buttons, valid for the call.
                let code = unsafe { read_pose6(self.dev, pose.position_m.as_mut_ptr(), pose.orientation.as_mut_ptr(), &mut buttons) };
                if code == 0 {
                    pose.orientation = quat_normalize(pose.orientation).ok_or_else(|| {
                        anyhow!(
                            "plug-in {}: nsd_read_pose6 gave the orientation {:?}, not a rotation",
                            self.path.display(),
                            pose.orientation
                        )
                    })?;
                }
                (code, "nsd_read_pose6", pose)
            }
        };
        if code != 0 {
            return Err(self.error(call, code));
        }
        if !pose.position_m.iter().all(|v| v.is_finite()) {
            bail!("plug-in {}: {call} gave the position {:?}", self.path.display(), pose.position_m);
        }
        Ok(DeviceState { pose, buttons })
    }
    fn write_force(&mut self, w: [f64; 6]) -> Result<()> {
        if self.dev.is_null() {
            bail!("plug-in {}: write after close", self.path.display());
        }
        let (code, call) = match self.abi {
            Abi::Planar { write_force, .. } => {
                let [fx, fy, tau] = wrench_to_planar(w);
                // SAFETY: dev is open.
                (unsafe { write_force(self.dev, fx, fy, tau) }, "nsd_write_force")
            }
            Abi::Spatial { write_wrench, .. } => {
                let (f, t) = ([w[0], w[1], w[2]], [w[3], w[4], w[5]]);
                // SAFETY: dev is open; two arrays of 3 doubles valid for the call.
                (unsafe { write_wrench(self.dev, f.as_ptr(), t.as_ptr()) }, "nsd_write_wrench")
            }
        };
        if code != 0 {
            return Err(self.error(call, code));
        }
        Ok(())
    }
    fn output(&self) -> DeviceOutput {
        self.output
    }
    fn close(&mut self) {
        if !self.dev.is_null() {
            // SAFETY: dev is open and is not used afterwards.
            unsafe { (self.close)(self.dev) };
            self.dev = std::ptr::null_mut();
        }
    }
}

impl Drop for PluginDevice {
    fn drop(&mut self) {
        self.close();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TRAJ: &str = "t_s,x_m,y_m,theta_rad\n0,0,0,0\n1,0.01,-0.02,0.1\n2,0.01,-0.02,0.1\n";
    /// 3D: along +x then a quarter turn about z (qw = qz = √½).
    const TRAJ3: &str = "t_s,x_m,y_m,z_m,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n1,0.01,-0.02,0.03,0.7071067811865476,0,0,0.7071067811865476\n";

    fn planar(p: &Pose6) -> [f64; 3] {
        p.to_planar()
    }

    #[test]
    fn trajectory_interpolates_holds_and_loops() {
        let t = Trajectory::parse(TRAJ, "t.csv", false).unwrap();
        assert!(!t.is_spatial());
        let (q, v) = t.sample(0.5);
        let q = planar(&q);
        assert!((q[0] - 0.005).abs() < 1e-15 && (q[1] + 0.01).abs() < 1e-15 && (q[2] - 0.05).abs() < 1e-15, "{q:?}");
        assert!((v[0] - 0.01).abs() < 1e-15 && (v[5] - 0.1).abs() < 1e-15 && v[2] == 0.0, "{v:?}");
        assert_eq!(t.sample(-1.0), (Pose6::default(), [0.0; 6]));
        let end = planar(&t.sample(5.0).0);
        assert!((end[0] - 0.01).abs() < 1e-15 && (end[1] + 0.02).abs() < 1e-15 && (end[2] - 0.1).abs() < 1e-15, "{end:?}");
        let l = Trajectory::parse(TRAJ, "t.csv", true).unwrap();
        let q = planar(&l.sample(2.5).0);
        assert!((q[0] - 0.005).abs() < 1e-15, "{q:?}");
    }

    #[test]
    fn a_3d_trajectory_is_read_and_interpolated() {
        let t = Trajectory::parse(TRAJ3, "t3.csv", false).unwrap();
        assert!(t.is_spatial());
        let (q, v) = t.sample(0.5);
        assert!((q.position_m[0] - 0.005).abs() < 1e-15 && (q.position_m[2] - 0.015).abs() < 1e-15, "{q:?}");
        // Half of the quarter turn: 45° about z, at π/2 rad/s.
        assert!((q.to_planar()[2] - std::f64::consts::FRAC_PI_4).abs() < 1e-12, "{q:?}");
        assert!((v[5] - std::f64::consts::FRAC_PI_2).abs() < 1e-12 && (v[2] - 0.03).abs() < 1e-15, "{v:?}");
        let e = Trajectory::parse("t_s,x_m,y_m,z_m,qw,qx,qy,qz\n0,0,0,0,2,0,0,0\n", "bad3.csv", false).unwrap_err().to_string();
        assert!(e.starts_with("bad3.csv: trajectory line 2: the quaternion"), "{e}");
    }

    #[test]
    fn a_buttons_column_is_read_in_3d_and_in_2d() {
        let text = "t_s,x_m,y_m,z_m,qw,qx,qy,qz,buttons\n# press at 1 s\n0,0,0,0,1,0,0,0,0\n1,0.01,0,0,1,0,0,0,1\n2,0.02,0,0,1,0,0,0,0\n";
        let mut d = ScriptedDevice::new(Trajectory::parse(text, "b3.csv", false).unwrap());
        let at = |d: &mut ScriptedDevice, t: f64| d.read_pose(t).unwrap();
        assert_eq!((at(&mut d, 0.5).buttons, at(&mut d, 1.0).buttons, at(&mut d, 1.9).buttons, at(&mut d, 2.5).buttons), (0, 1, 1, 0));
        assert!((at(&mut d, 1.5).pose.position_m[0] - 0.015).abs() < 1e-15);
        let t2 = Trajectory::parse("t_s,x_m,y_m,theta_rad,buttons\n0,0,0,0,2\n1,0.01,0,0,0\n", "b2.csv", false).unwrap();
        assert_eq!((t2.buttons_at(-1.0), t2.buttons_at(0.2), t2.buttons_at(1.0)), (2, 2, 0));
        let e = Trajectory::parse("t_s,x_m,y_m,z_m,qw,qx,qy,qz,buttons\n0,0,0,0,1,0,0,0,x\n", "bad.csv", false).unwrap_err().to_string();
        assert_eq!(e, "bad.csv: trajectory line 2: column buttons: `x` is not an unsigned integer");
        // Without the column: no buttons.
        assert_eq!(Trajectory::parse(TRAJ3, "t3", false).unwrap().buttons_at(0.5), 0);
    }

    #[test]
    fn trajectory_errors_name_file_and_line() {
        let e = |text: &str| Trajectory::parse(text, "traj.csv", false).unwrap_err().to_string();
        assert_eq!(
            e("t,x,y,th\n0,0,0,0\n"),
            "traj.csv: trajectory line 1: the header must be t_s,x_m,y_m,theta_rad, found a header whose column 1 is not t_s"
        );
        assert!(e("t_s,x_m,y_m,theta_rad\n0,0,0,0\n1,abc,0,0\n").starts_with("traj.csv: trajectory line 3: column x_m"));
        assert_eq!(e("t_s,x_m,y_m,theta_rad\n0,0,0,0\n0,1,0,0\n"), "traj.csv: trajectory line 3: t_s = 0 does not increase (previous 0)");
        assert!(
            e("t_s,x_m,y_m,theta_rad\n0,0,0,0\n1,0,0\n").starts_with("traj.csv: trajectory line 3: "),
            "{}",
            e("t_s,x_m,y_m,theta_rad\n0,0,0,0\n1,0,0\n")
        );
    }

    #[test]
    fn scripted_records_forces_and_ignores_them() {
        let mut d = ScriptedDevice::new(Trajectory::parse(TRAJ, "t", false).unwrap());
        d.write_force([3.0, 4.0, 12.0, 0.0, 0.0, 0.1]).unwrap();
        let q = d.read_pose(1.0).unwrap().pose.to_planar();
        assert!((q[0] - 0.01).abs() < 1e-15 && (q[1] + 0.02).abs() < 1e-15 && (q[2] - 0.1).abs() < 1e-15, "{q:?}");
        assert_eq!((d.last_force, d.force_writes, d.max_force_n), ([3.0, 4.0, 12.0, 0.0, 0.0, 0.1], 1, 13.0));
    }

    #[test]
    fn virtual_operator_tracks_and_yields_to_force() {
        let traj = Trajectory::parse("t_s,x_m,y_m,theta_rad\n0,0,0,0\n1,0.02,0,0\n", "t", false).unwrap();
        let p = OperatorParams::default();
        let mut d = VirtualOperator::new(traj.clone(), p);
        for k in 0..=2000 {
            d.read_pose(k as f64 * 1e-3).unwrap();
        }
        assert!((d.state().q.position_m[0] - 0.02).abs() < 1e-4, "{:?}", d.state());
        // A constant resisting force F settles at q_ref + F/(kp) (static balance kp·e = F).
        let mut d = VirtualOperator::new(traj, p);
        for k in 0..=4000 {
            d.read_pose(k as f64 * 1e-3).unwrap();
            d.write_force([-1.5, 0.0, 0.0, 0.0, 0.0, 0.0]).unwrap();
        }
        let expect = 0.02 - 1.5 / p.kp[0];
        assert!((d.state().q.position_m[0] - expect).abs() < 1e-5, "{:?} vs {expect}", d.state());
        assert_eq!(d.state().rendered, [-1.5, 0.0, 0.0, 0.0, 0.0, 0.0]);
    }

    /// In 3D the hand follows a 3D path (position and a quarter turn) and a torque about z holds
    /// it back by τ/kp_rot, a force along z by F/kp.
    #[test]
    fn virtual_operator_follows_a_3d_path_and_yields_to_a_3d_wrench() {
        let traj = Trajectory::parse(TRAJ3, "t3", false).unwrap();
        let p = OperatorParams::default();
        let mut d = VirtualOperator::new(traj.clone(), p);
        for k in 0..=3000 {
            d.read_pose(k as f64 * 1e-3).unwrap();
        }
        let q = d.state().q;
        assert!((q.position_m[2] - 0.03).abs() < 1e-4 && (q.position_m[1] + 0.02).abs() < 1e-4, "{q:?}");
        assert!((q.to_planar()[2] - std::f64::consts::FRAC_PI_2).abs() < 1e-3, "{q:?}");
        let mut d = VirtualOperator::new(traj, p);
        let (fz, tz) = (0.9, -0.006);
        for k in 0..=6000 {
            d.read_pose(k as f64 * 1e-3).unwrap();
            d.write_force([0.0, 0.0, fz, 0.0, 0.0, tz]).unwrap();
        }
        let q = d.state().q;
        assert!((q.position_m[2] - (0.03 + fz / p.kp[2])).abs() < 1e-5, "{q:?}");
        assert!((q.to_planar()[2] - (std::f64::consts::FRAC_PI_2 + tz / p.kp[5])).abs() < 1e-4, "{q:?}");
        let n: f64 = q.orientation.iter().map(|v| v * v).sum();
        assert!((n - 1.0).abs() < 1e-12);
    }
}
