//! needlesim in Foxglove: a simulation state as Foxglove scene entities and a force sample, the
//! MCAP channels that carry them in a recording, and a live WebSocket endpoint (Foxglove's
//! ws-protocol, with bounded clients and queues) with a channel pair per session.
//!
//! The service layer converts its own records into [`SceneFrame`] (plain data: positions in
//! metres in the tissue's world frame, 2D sessions embedded at z = 0) and calls [`scene_update`] /
//! [`ForceSample`]; this crate knows neither the real-time loop nor the project's protocol.
//!
//! Topics (one pair per session; in a recording, the session is the file):
//! - `/needlesim/<session>/scene` — `foxglove.SceneUpdate` (protobuf): entities `tissue` (the
//!   boundary surface, displaced and coloured by displacement magnitude), `needle` (base → tip
//!   line), `contacts` (a sphere per contact point: stuck blue, slipping orange, tip magenta),
//!   `targets` (a sphere of the target's radius at its displaced centre: green when hit). Frame id
//!   [`FRAME_ID`].
//! - `/needlesim/<session>/force` — [`ForceSample`] as JSON (schema [`FORCE_SCHEMA_JSON`]): the
//!   base force (N) and torque (N·m) in the world frame, the inserted depth (m), for the Plot panel.

pub use foxglove;

pub mod live;
pub mod mcap_channels;
pub mod scene;
mod ws;

pub use live::{FoxgloveLive, LiveError, LiveOptions, LiveStats, SessionChannels};
pub use mcap_channels::McapChannels;
pub use scene::{
    FORCE_SCHEMA_JSON, FORCE_SCHEMA_NAME, FRAME_ID, ForceSample, PointState, SceneFrame, ScenePoint, SceneTarget, Surface, Vec3Json,
    scene_update,
};

/// The scene topic of a session.
pub fn scene_topic(session: &str) -> String {
    format!("/needlesim/{session}/scene")
}

/// The force topic of a session.
pub fn force_topic(session: &str) -> String {
    format!("/needlesim/{session}/force")
}
