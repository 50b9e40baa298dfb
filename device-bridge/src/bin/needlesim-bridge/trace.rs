//! The bridge's per-period trace (`--trace CSV`): 2D or 6-DOF columns by the session's dimension.

use std::io::Write;

use anyhow::{Context, Result};
use needlesim_bridge::device::DeviceState;
use needlesim_bridge::render::RenderOutput;
use needlesim_channel::spatial::wrench_to_planar;

use crate::Cli;
use crate::link::Exchange;

pub(crate) type Trace = std::io::BufWriter<std::fs::File>;

/// The `--trace` CSV with its header (the 2D or the 6-DOF columns), if asked for.
pub(crate) fn open_trace(cli: &Cli, planar: bool) -> Result<Option<Trace>> {
    let Some(p) = &cli.trace else { return Ok(None) };
    let f = std::fs::File::create(p).with_context(|| format!("--trace {}: cannot create", p.display()))?;
    let mut w = std::io::BufWriter::new(f);
    if planar {
        writeln!(w, "t_s,counter,x_m,y_m,theta_rad,fresh,tick,server_fx_n,server_fy_n,server_torque_nm,fx_n,fy_n,torque_nm,gain")?;
    } else {
        writeln!(
            w,
            "t_s,counter,x_m,y_m,z_m,qw,qx,qy,qz,fresh,tick,server_fx_n,server_fy_n,server_fz_n,server_tx_nm,server_ty_nm,server_tz_nm,\
             fx_n,fy_n,fz_n,tx_nm,ty_nm,tz_nm,gain"
        )?;
    }
    Ok(Some(w))
}

/// One period's trace row.
pub(crate) fn write_trace_row(
    w: &mut Trace,
    planar: bool,
    t_s: f64,
    counter: u64,
    state: &DeviceState,
    ex: &Exchange,
    out: &RenderOutput,
) -> Result<()> {
    let fresh = ex.fresh.is_some() as u8;
    if planar {
        let [x, y, th] = state.pose.to_planar();
        let (sw, rw) = (wrench_to_planar(ex.last_wrench), wrench_to_planar(out.wrench));
        writeln!(
            w,
            "{t_s},{counter},{x},{y},{th},{fresh},{},{},{},{},{},{},{},{}",
            ex.last_tick, sw[0], sw[1], sw[2], rw[0], rw[1], rw[2], out.gain
        )?;
    } else {
        // Written field by field: nothing is allocated in the device loop.
        write!(w, "{t_s},{counter}")?;
        for v in state.pose.position_m.iter().chain(&state.pose.orientation) {
            write!(w, ",{v}")?;
        }
        write!(w, ",{fresh},{}", ex.last_tick)?;
        for v in ex.last_wrench.iter().chain(&out.wrench) {
            write!(w, ",{v}")?;
        }
        writeln!(w, ",{}", out.gain)?;
    }
    Ok(())
}
