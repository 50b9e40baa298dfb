//! Haptic devices behind one trait: a scripted trajectory, a simulated operator's hand on a device,
//! and real devices through a C plug-in (`include/needlesim_device.h`).

use std::ffi::{CStr, CString, c_char, c_int, c_void};
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, anyhow, bail};

/// What a device reports each period.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DeviceState {
    pub x_m: f64,
    pub y_m: f64,
    pub theta_rad: f64,
    /// A bit per button, 1 = pressed.
    pub buttons: u32,
}

impl DeviceState {
    pub fn pose(&self) -> [f64; 3] {
        [self.x_m, self.y_m, self.theta_rad]
    }
}

/// A haptic device, driven from one thread at the device rate.
pub trait Device {
    fn name(&self) -> &str;
    /// The pose at `t_s` seconds since the loop started (devices with their own clock may ignore it).
    fn read_pose(&mut self, t_s: f64) -> Result<DeviceState>;
    /// Command this wrench (Fx N, Fy N, τ N·m) until the next call.
    fn write_force(&mut self, wrench: [f64; 3]) -> Result<()>;
    /// Release the device (idempotent). The bridge writes a zero force before.
    fn close(&mut self);
}

// ---------------------------------------------------------------------------------------------
// Trajectory

/// A trajectory CSV (`t_s,x_m,y_m,theta_rad`, parsed by needlesim-trajectory), linearly
/// interpolated, optionally replayed in a loop.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    inner: needlesim_trajectory::Trajectory,
    /// Replay from the start after the end (else hold the last pose).
    pub looped: bool,
}

impl Trajectory {
    /// Reads a CSV file; errors name the file and the line.
    pub fn load(path: impl AsRef<Path>, looped: bool) -> Result<Self> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).with_context(|| format!("trajectory {}: cannot read", path.display()))?;
        Self::parse(&text, &path.display().to_string(), looped)
    }

    /// Parses CSV text; `name` leads error messages (`name: trajectory line N: …`).
    pub fn parse(text: &str, name: &str, looped: bool) -> Result<Self> {
        let inner = needlesim_trajectory::Trajectory::parse_csv(text).map_err(|e| anyhow!("{name}: {e}"))?;
        Ok(Self { inner, looped })
    }

    /// Duration from the first to the last row (s).
    pub fn duration_s(&self) -> f64 {
        self.inner.duration_s()
    }

    /// Pose and velocity (slope of the segment) at time `t_s` (before the start: the first pose, at rest).
    pub fn sample(&self, t_s: f64) -> ([f64; 3], [f64; 3]) {
        let (t0, d) = (self.inner.span_s().0, self.duration_s());
        let mut t = t_s;
        if self.looped && d > 0.0 && t > t0 + d {
            t = t0 + (t - t0).rem_euclid(d);
        }
        let (q, v) = self.inner.pose_and_velocity_at(t);
        ([q.x_m, q.y_m, q.theta_rad], [v.x_m, v.y_m, v.theta_rad])
    }
}

// ---------------------------------------------------------------------------------------------
// Scripted

/// Replays a trajectory; forces are recorded but move nothing.
#[derive(Debug, Clone)]
pub struct ScriptedDevice {
    traj: Trajectory,
    /// The last wrench written.
    pub last_force: [f64; 3],
    /// How many wrenches were written.
    pub force_writes: u64,
    /// The largest |(Fx, Fy)| written.
    pub max_force_n: f64,
}

impl ScriptedDevice {
    pub fn new(traj: Trajectory) -> Self {
        Self { traj, last_force: [0.0; 3], force_writes: 0, max_force_n: 0.0 }
    }
}

impl Device for ScriptedDevice {
    fn name(&self) -> &str {
        "scripted"
    }
    fn read_pose(&mut self, t_s: f64) -> Result<DeviceState> {
        let (q, _) = self.traj.sample(t_s);
        Ok(DeviceState { x_m: q[0], y_m: q[1], theta_rad: q[2], buttons: 0 })
    }
    fn write_force(&mut self, wrench: [f64; 3]) -> Result<()> {
        self.last_force = wrench;
        self.force_writes += 1;
        self.max_force_n = self.max_force_n.max(wrench[0].hypot(wrench[1]));
        Ok(())
    }
    fn close(&mut self) {}
}

// ---------------------------------------------------------------------------------------------
// Virtual operator

/// The simulated hand + device: per axis (x, y translational; θ rotational)
/// `m·a = kp (q_ref − q) + kd (v_ref − v) + w_rendered − b·v`, integrated by semi-implicit Euler
/// (`v ← v + Δt·a`, then `q ← q + Δt·v`) once per `read_pose`, with Δt the time since the previous call.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OperatorParams {
    /// Mass (kg) in x and y, rotational inertia (kg·m²) in θ.
    pub mass: [f64; 3],
    /// Damping: N·s/m in x, y; N·m·s/rad in θ.
    pub damping: [f64; 3],
    /// PD proportional gains: N/m in x, y; N·m/rad in θ.
    pub kp: [f64; 3],
    /// PD derivative gains: N·s/m in x, y; N·m·s/rad in θ.
    pub kd: [f64; 3],
}

impl Default for OperatorParams {
    fn default() -> Self {
        // A hand holding a desktop device: 0.3 kg, a 300 N/m grip, critically damped-ish.
        Self { mass: [0.3, 0.3, 1e-4], damping: [2.0, 2.0, 1e-3], kp: [300.0, 300.0, 0.3], kd: [15.0, 15.0, 0.01] }
    }
}

/// The virtual operator's state.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct OperatorState {
    pub t_s: f64,
    pub q: [f64; 3],
    pub v: [f64; 3],
    /// The wrench last rendered on it.
    pub rendered: [f64; 3],
    /// The PD wrench of the last step.
    pub pd: [f64; 3],
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
            let p = &self.params;
            for i in 0..3 {
                s.pd[i] = p.kp[i] * (q_ref[i] - s.q[i]) + p.kd[i] * (v_ref[i] - s.v[i]);
                let a = (s.pd[i] + s.rendered[i] - p.damping[i] * s.v[i]) / p.mass[i];
                s.v[i] += dt * a;
                s.q[i] += dt * s.v[i];
            }
            s.t_s = t_s;
        }
        if !s.q.iter().chain(&s.v).all(|x| x.is_finite()) {
            bail!("virtual operator diverged at t = {t_s} s (q = {:?}, v = {:?})", s.q, s.v);
        }
        Ok(DeviceState { x_m: s.q[0], y_m: s.q[1], theta_rad: s.q[2], buttons: 0 })
    }
    fn write_force(&mut self, wrench: [f64; 3]) -> Result<()> {
        self.state.rendered = wrench;
        Ok(())
    }
    fn close(&mut self) {}
}

// ---------------------------------------------------------------------------------------------
// Plug-in

/// The ABI version this bridge speaks (`NSD_ABI_VERSION` in `include/needlesim_device.h`).
pub const PLUGIN_ABI_VERSION: c_int = 1;

type AbiVersionFn = unsafe extern "C" fn() -> c_int;
type OpenFn = unsafe extern "C" fn(*const c_char) -> *mut c_void;
type ReadPoseFn = unsafe extern "C" fn(*mut c_void, *mut f64, *mut f64, *mut f64, *mut u32) -> c_int;
type WriteForceFn = unsafe extern "C" fn(*mut c_void, f64, f64, f64) -> c_int;
type CloseFn = unsafe extern "C" fn(*mut c_void);
type LastErrorFn = unsafe extern "C" fn(*mut c_void) -> *const c_char;

/// A device in a shared library implementing `include/needlesim_device.h`.
pub struct PluginDevice {
    path: PathBuf,
    name: String,
    dev: *mut c_void,
    read_pose: ReadPoseFn,
    write_force: WriteForceFn,
    close: CloseFn,
    last_error: LastErrorFn,
    // Last field: dropped (dlclose) after everything that points into it.
    lib: libloading::Library,
}

impl PluginDevice {
    /// Loads `path`, checks `nsd_abi_version()`, and calls `nsd_open(config)`.
    pub fn open(path: impl AsRef<Path>, config: &str) -> Result<Self> {
        let path = path.as_ref().to_path_buf();
        let p = path.display().to_string();
        // SAFETY: loading a library runs its initialisers; the user chose to trust this plug-in.
        let lib = unsafe { libloading::Library::new(&path) }.with_context(|| format!("plug-in {p}: cannot load"))?;
        // SAFETY: the types are those of the header; a library exporting these names with other
        // signatures breaks the plug-in contract.
        let (abi, open, read_pose, write_force, close, last_error) = unsafe {
            let sym = |name: &str| format!("plug-in {p}: missing symbol {name} (see include/needlesim_device.h)");
            (
                *lib.get::<AbiVersionFn>(b"nsd_abi_version\0").with_context(|| sym("nsd_abi_version"))?,
                *lib.get::<OpenFn>(b"nsd_open\0").with_context(|| sym("nsd_open"))?,
                *lib.get::<ReadPoseFn>(b"nsd_read_pose\0").with_context(|| sym("nsd_read_pose"))?,
                *lib.get::<WriteForceFn>(b"nsd_write_force\0").with_context(|| sym("nsd_write_force"))?,
                *lib.get::<CloseFn>(b"nsd_close\0").with_context(|| sym("nsd_close"))?,
                *lib.get::<LastErrorFn>(b"nsd_last_error\0").with_context(|| sym("nsd_last_error"))?,
            )
        };
        // SAFETY: plug-in calls per the ABI.
        let version = unsafe { abi() };
        if version != PLUGIN_ABI_VERSION {
            bail!("plug-in {p}: ABI version {version}, this bridge speaks {PLUGIN_ABI_VERSION}");
        }
        let c = CString::new(config).map_err(|_| anyhow!("plug-in {p}: the config string contains a NUL byte"))?;
        // SAFETY: a valid NUL-terminated string that outlives the call.
        let dev = unsafe { open(c.as_ptr()) };
        if dev.is_null() {
            // SAFETY: nsd_last_error(NULL) is defined by the ABI.
            let msg = unsafe { error_string(last_error(std::ptr::null_mut())) };
            bail!("plug-in {p}: nsd_open failed: {msg}");
        }
        let name = format!("plugin:{}", path.file_name().map_or(p.clone(), |f| f.to_string_lossy().into_owned()));
        Ok(Self { path, name, dev, read_pose, write_force, close, last_error, lib })
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
        let mut s = DeviceState::default();
        // SAFETY: dev is open; the out-pointers are valid for the call.
        let code = unsafe { (self.read_pose)(self.dev, &mut s.x_m, &mut s.y_m, &mut s.theta_rad, &mut s.buttons) };
        if code != 0 {
            return Err(self.error("nsd_read_pose", code));
        }
        Ok(s)
    }
    fn write_force(&mut self, w: [f64; 3]) -> Result<()> {
        if self.dev.is_null() {
            bail!("plug-in {}: write after close", self.path.display());
        }
        // SAFETY: dev is open.
        let code = unsafe { (self.write_force)(self.dev, w[0], w[1], w[2]) };
        if code != 0 {
            return Err(self.error("nsd_write_force", code));
        }
        Ok(())
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

    #[test]
    fn trajectory_interpolates_holds_and_loops() {
        let t = Trajectory::parse(TRAJ, "t.csv", false).unwrap();
        let (q, v) = t.sample(0.5);
        assert!((q[0] - 0.005).abs() < 1e-15 && (q[1] + 0.01).abs() < 1e-15 && (q[2] - 0.05).abs() < 1e-15);
        assert!((v[0] - 0.01).abs() < 1e-15);
        assert_eq!(t.sample(-1.0), ([0.0; 3], [0.0; 3]));
        assert_eq!(t.sample(5.0).0, [0.01, -0.02, 0.1]);
        let l = Trajectory::parse(TRAJ, "t.csv", true).unwrap();
        let (q, _) = l.sample(2.5);
        assert!((q[0] - 0.005).abs() < 1e-15, "{q:?}");
    }

    #[test]
    fn trajectory_errors_name_file_and_line() {
        let e = |text: &str| Trajectory::parse(text, "traj.csv", false).unwrap_err().to_string();
        assert_eq!(e("t,x,y,th\n0,0,0,0\n"), "traj.csv: trajectory line 1: the header must be t_s,x_m,y_m,theta_rad, found t,x,y,th");
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
        d.write_force([3.0, 4.0, 0.1]).unwrap();
        assert_eq!(d.read_pose(1.0).unwrap().pose(), [0.01, -0.02, 0.1]);
        assert_eq!((d.last_force, d.force_writes, d.max_force_n), ([3.0, 4.0, 0.1], 1, 5.0));
    }

    #[test]
    fn virtual_operator_tracks_and_yields_to_force() {
        let traj = Trajectory::parse("t_s,x_m,y_m,theta_rad\n0,0,0,0\n1,0.02,0,0\n", "t", false).unwrap();
        let p = OperatorParams::default();
        let mut d = VirtualOperator::new(traj.clone(), p);
        for k in 0..=2000 {
            d.read_pose(k as f64 * 1e-3).unwrap();
        }
        assert!((d.state().q[0] - 0.02).abs() < 1e-4, "{:?}", d.state());
        // A constant resisting force F settles at q_ref + F/(kp) (static balance kp·e = F).
        let mut d = VirtualOperator::new(traj, p);
        for k in 0..=4000 {
            d.read_pose(k as f64 * 1e-3).unwrap();
            d.write_force([-1.5, 0.0, 0.0]).unwrap();
        }
        let expect = 0.02 - 1.5 / p.kp[0];
        assert!((d.state().q[0] - expect).abs() < 1e-5, "{:?} vs {expect}", d.state());
        assert_eq!(d.state().rendered, [-1.5, 0.0, 0.0]);
    }
}
