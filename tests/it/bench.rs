//! `needlesim-lab bench --quick --json` through the real binary: one JSON object with the
//! required keys for ours, dense and naive at 50×50, finite positive figures, the SVG plot, and
//! the property that ours' step is faster than a full solve per tick.

use std::process::Command;

use needlesim_tests::{TempDir, bin, run, text};
use serde_json::Value;

const KEYS: [&str; 5] = ["setup_s", "step_p50_s", "step_p99_s", "step_max_s", "peak_mem_bytes"];

fn result<'a>(results: &'a [Value], mesh: &str, solver: &str) -> &'a Value {
    results.iter().find(|r| r["mesh"] == mesh && r["solver"] == solver).unwrap_or_else(|| panic!("no result for {solver} at {mesh}"))
}

#[test]
fn quick_bench_reports_the_three_solvers() {
    let tmp = TempDir::new("bench");
    let plot = tmp.join("step_time.svg");
    let started = std::time::Instant::now();
    let o = run(Command::new(bin("needlesim-lab")).args(["bench", "--quick", "--json", "--plot"]).arg(&plot));
    let (out, err) = text(&o);
    assert!(o.status.success(), "bench failed: {err}");
    assert!(!err.contains("panicked"), "{err}");
    eprintln!("bench --quick took {:.1} s", started.elapsed().as_secs_f64());
    let v: Value = serde_json::from_str(out.trim()).unwrap_or_else(|e| panic!("stdout is not one JSON object ({e}): {out}"));
    assert!(v["machine"].as_str().is_some_and(|m| !m.is_empty()), "machine: {}", v["machine"]);
    let results = v["results"].as_array().expect("results is an array");
    for solver in ["ours", "dense", "naive"] {
        let r = result(results, "50x50", solver);
        assert_eq!(r["n_nodes"], 2500, "{r}");
        for key in KEYS {
            let x = r[key].as_f64().unwrap_or_else(|| panic!("{solver} at 50x50: {key} is not a number: {r}"));
            assert!(x.is_finite() && x > 0.0, "{solver} at 50x50: {key} = {x}");
        }
        let (p50, p99, max) = (r["step_p50_s"].as_f64().unwrap(), r["step_p99_s"].as_f64().unwrap(), r["step_max_s"].as_f64().unwrap());
        assert!(p50 <= p99 && p99 <= max, "{solver}: percentiles out of order: {r}");
    }
    let ours = result(results, "50x50", "ours")["step_p50_s"].as_f64().unwrap();
    let naive = result(results, "50x50", "naive")["step_p50_s"].as_f64().unwrap();
    assert!(ours < naive, "ours' step p50 ({ours} s) is not below a full solve per tick ({naive} s)");
    // The dense inverse holds n_free² doubles: its peak heap is far above ours'.
    let mem = |s| result(results, "50x50", s)["peak_mem_bytes"].as_f64().unwrap();
    assert!(mem("dense") > 8.0 * 4900.0 * 4900.0, "dense peak {} below its inverse", mem("dense"));
    // The static comparison is present for every mesh (timed by scipy, or skipped with a reason).
    let statics = v["static"]["results"].as_array().expect("static.results is an array");
    assert!(statics.iter().any(|s| s["mesh"] == "50x50"), "no static result at 50x50");
    for s in statics {
        assert!(s["ours_solve_s"].as_f64().is_some_and(|t| t > 0.0), "{s}");
        assert!(s["scipy"].is_object(), "{s}");
    }
    let svg = std::fs::read_to_string(&plot).expect("the plot is written");
    assert!(svg.contains("<svg") && svg.contains("naive"), "not an SVG plot with a legend");
}

#[test]
fn bench_rejects_a_too_small_grid() {
    let o = run(Command::new(bin("needlesim-lab")).args(["bench", "--quick", "--json", "--sizes", "2"]));
    let (out, err) = text(&o);
    assert!(!o.status.success(), "a 2×2 grid was accepted: {out}");
    assert!(err.contains("grid size 2 is too small"), "{err}");
    assert!(out.is_empty(), "{out}");
}
