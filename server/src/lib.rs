//! needlesim-server as a library: the scene format, the exchange format of the validation suite,
//! and the offline commands (solve, simulate, bench), shared by the `needlesim-server` binary and the tests.

pub mod bench;
pub mod exchange;
pub mod scene;
pub mod simulate;
