//! The integration tests, one test binary (as ripgrep does) so that tokio, tonic and the rest are
//! linked once rather than once per file: each file of tests/it/ is a module, its tests are named
//! `MODULE::TEST` (`cargo test -p needlesim-tests server_e2e::`); the helpers are the crate's
//! library, tests/support/lib.rs. All tests share one process: the ones that run or time a 1 kHz
//! session take turns through [`needlesim_tests::REALTIME`].

mod access_e2e;
mod api_limits;
mod api_limits_issue35;
mod bench;
mod bridge3d;
mod bridge_e2e;
mod cli;
mod cli3d;
mod cli_errors;
mod contact_points;
mod convergence;
mod docs;
mod file_refs;
mod fleet;
mod fleet_alloc;
mod flexible_e2e;
mod foxglove;
mod identify_fit;
mod identify_track;
mod meshes3d;
mod plan;
mod plan3;
mod python_client;
mod python_client3d;
mod python_package;
mod rate_physics;
mod scenes3d;
mod server_e2e;
mod session3d;
mod session_close;
mod sim3;
mod simulate;
mod simulate3;
mod stream_limits;
mod tour;
mod training;
mod training_device;
mod training_live;
mod transport;
mod validation;
mod vtk_meshes;
mod web;
