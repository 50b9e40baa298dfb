//! Issue 19, rate dependence through the real `needlesim-server simulate` binary: a
//! viscoelastic block under a step displacement relaxes as the closed-form standard linear solid.

use std::path::Path;
use std::process::Command;

use needlesim_tests::{TempDir, bin, run, text};

/// The paper phantom's block (19 × 19, plane stress), contact at material points, a needle tip
/// that never punctures (1 kN), with `extra` TOML appended.
fn block_scene(extra: &str) -> String {
    format!(
        r#"name = "sls-block"
tick_rate_hz = 1000
fixed = ["bottom"]
[mesh]
type = "grid"
nx = 19
ny = 19
width_m = 0.1
height_m = 0.1
[plane]
model = "stress"
thickness_m = 0.01
[[regions]]
name = "tissue"
young_modulus_pa = 30e3
poisson_ratio = 0.45
puncture_force_n = 1000
cutting_force_n = 1000
[needle]
length_m = 0.1
base = [0.05, 0.205, -1.5707963267948966]
contact = "points"
[limits]
max_base_step_m = 0.01
{extra}
"#
    )
}

/// Runs `simulate` of `scene` (TOML text) along `traj` (CSV text) in `dir`; returns each tick's
/// base force `(fx, fy)`.
fn simulate_forces(dir: &TempDir, label: &str, scene: &str, traj: &str) -> Vec<[f64; 2]> {
    let (scene_path, traj_path, out_path) =
        (dir.join(&format!("{label}.toml")), dir.join(&format!("{label}.csv")), dir.join(&format!("{label}.out.csv")));
    std::fs::write(&scene_path, scene).unwrap();
    std::fs::write(&traj_path, traj).unwrap();
    let o = run(Command::new(bin("needlesim-server")).arg("simulate").args([
        "--scene",
        scene_path.to_str().unwrap(),
        "--trajectory",
        traj_path.to_str().unwrap(),
        "-o",
        out_path.to_str().unwrap(),
    ]));
    let (_, err) = text(&o);
    assert!(o.status.success() && !err.contains("panicked"), "simulate {label}: {err}");
    read_forces(&out_path)
}

fn read_forces(path: &Path) -> Vec<[f64; 2]> {
    let csv = std::fs::read_to_string(path).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name}"));
    let (cx, cy) = (col("fx_n"), col("fy_n"));
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            [v[cx], v[cy]]
        })
        .collect()
}

/// The standard linear solid's force at every tick for the elastic force history `f_el` (linear
/// between ticks, zero before the first), $g(t) = g_\infty + (1 - g_\infty) e^{-t/\tau}$:
/// $F(t_n) = \sum_j \frac{F_j - F_{j-1}}{\Delta t} \int_{t_{j-1}}^{t_j} g(t_n - s)\,ds$, each
/// integral in closed form, summed directly (not recursively).
fn sls_closed_form(g_inf: f64, tau_s: f64, dt: f64, f_el: &[[f64; 2]]) -> Vec<[f64; 2]> {
    (0..f_el.len())
        .map(|n| {
            let mut out = [0.0; 2];
            for j in 0..=n {
                let prev = if j == 0 { [0.0; 2] } else { f_el[j - 1] };
                let (age0, age1) = ((n - j + 1) as f64 * dt, (n - j) as f64 * dt);
                let int = g_inf * dt + (1.0 - g_inf) * tau_s * ((-age1 / tau_s).exp() - (-age0 / tau_s).exp());
                for k in 0..2 {
                    out[k] += (f_el[j][k] - prev[k]) / dt * int;
                }
            }
            out
        })
        .collect()
}

/// Item 2's first "Done when": the needle's tip presses the block (it never punctures), is
/// stepped 2 mm in one tick and held for 5 τ. The viscoelastic scene's force follows the
/// closed-form SLS of the elastic scene's force history to 1e-6 of the peak at every tick, and
/// relaxes to g∞ of the elastic force.
#[test]
fn a_viscoelastic_block_under_a_step_relaxes_as_the_closed_form_sls() {
    let dir = TempDir::new("sls-block");
    let (g_inf, tau_s) = (0.4, 0.25);
    // 0.53 s at 10 mm/s (the tip 0.3 mm into the block), a 2 mm step in one tick, held 1.25 s.
    let traj = "t_s,x_m,y_m,theta_rad\n0,0.05,0.205,-1.5707963267948966\n0.53,0.05,0.1997,-1.5707963267948966\n\
                0.531,0.05,0.1977,-1.5707963267948966\n1.781,0.05,0.1977,-1.5707963267948966\n";
    let elastic = simulate_forces(&dir, "elastic", &block_scene(""), traj);
    let visco = simulate_forces(
        &dir,
        "visco",
        &block_scene(&format!("[viscoelastic]\nlong_term_ratio = {g_inf}\nrelaxation_time_s = {tau_s}\n")),
        traj,
    );
    assert_eq!(elastic.len(), 1782);
    assert_eq!(visco.len(), elastic.len());
    let closed = sls_closed_form(g_inf, tau_s, 1e-3, &elastic);
    let peak = visco.iter().map(|f| f[0].hypot(f[1])).fold(0.0, f64::max);
    assert!(peak > 0.05, "the step loads the block: peak {peak} N");
    let worst = visco.iter().zip(&closed).map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1])).fold(0.0, f64::max);
    assert!(worst <= 1e-6 * peak, "largest deviation from the closed form {worst:e} N (peak {peak} N)");
    // The hold's last tick, 5 τ after the step: within (1 − g∞) e^{-5} (one-tick ramp factor) of g∞.
    let (fe, fv) = (elastic.last().unwrap()[1], visco.last().unwrap()[1]);
    let ramp = tau_s / 1e-3 * ((1e-3 / tau_s).exp() - 1.0);
    let rest = fv / fe - g_inf;
    assert!(rest > 0.0 && rest <= (1.0 - g_inf) * (-5.0f64).exp() * ramp, "end {fv} N, elastic {fe} N");
    eprintln!(
        "simulate SLS block: peak {peak:.4} N, worst deviation {worst:.2e} N ({:.1e} of peak), end {fv:.5} N = {:.5} × elastic",
        worst / peak,
        fv / fe
    );
}
