//! A simulation state as Foxglove's well-known scene schema (`foxglove.SceneUpdate`) and the force
//! sample of the Plot panel.
use foxglove::messages::{
    Color, Duration, LinePrimitive, Point3, Pose, Quaternion, SceneEntity, SceneUpdate, SpherePrimitive, Timestamp, TriangleListPrimitive,
    Vector3, line_primitive::Type as LineType,
};
use serde::Serialize;

/// The frame every entity is expressed in: the tissue's world frame (metres).
pub const FRAME_ID: &str = "tissue";

/// The tissue's boundary: reference positions of its nodes (m) and triangles over them (indices
/// into `positions_m`, outward or not: Foxglove draws both sides).
#[derive(Debug, Clone, Default)]
pub struct Surface {
    pub positions_m: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

/// A contact point's state, as the viewer colours it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PointState {
    Stuck,
    Slipping,
    Tip,
    Other,
}

#[derive(Debug, Clone, Copy)]
pub struct ScenePoint {
    /// The point's deformed position (m, world).
    pub position_m: [f64; 3],
    pub state: PointState,
}

#[derive(Debug, Clone, Copy)]
pub struct SceneTarget {
    /// The displaced centre (m, world).
    pub centre_m: [f64; 3],
    pub radius_m: f64,
    pub hit: bool,
}

/// One state of a session, borrowed from the caller's buffers.
#[derive(Debug, Clone, Copy)]
pub struct SceneFrame<'a> {
    /// Simulation time (ns since the session started).
    pub time_ns: u64,
    /// The displacement (m) of each surface node, in `Surface::positions_m`'s order, or `None`
    /// (the surface is drawn undeformed, in one colour).
    pub surface_displacement_m: Option<&'a [[f64; 3]]>,
    /// The needle from base to tip (m, world); at least two points to be drawn.
    pub needle_m: &'a [[f64; 3]],
    pub points: &'a [ScenePoint],
    pub targets: &'a [SceneTarget],
}

fn timestamp(time_ns: u64) -> Timestamp {
    Timestamp::new((time_ns / 1_000_000_000) as u32, (time_ns % 1_000_000_000) as u32)
}

fn rgba(r: f64, g: f64, b: f64, a: f64) -> Color {
    Color { r, g, b, a }
}

fn p3([x, y, z]: [f64; 3]) -> Point3 {
    Point3 { x, y, z }
}

fn identity_pose() -> Pose {
    Pose { position: Some(Vector3 { x: 0.0, y: 0.0, z: 0.0 }), orientation: Some(Quaternion { x: 0.0, y: 0.0, z: 0.0, w: 1.0 }) }
}

fn at(position_m: [f64; 3]) -> Pose {
    let [x, y, z] = position_m;
    Pose { position: Some(Vector3 { x, y, z }), orientation: Some(Quaternion { x: 0.0, y: 0.0, z: 0.0, w: 1.0 }) }
}

/// Displacement magnitude `t` ∈ [0, 1] of the scale → white, through yellow, to red.
pub fn heat(t: f64) -> Color {
    let s = t.clamp(0.0, 1.0);
    if s < 0.5 { rgba(1.0, 1.0, 1.0 - 1.8 * s, 0.9) } else { rgba(1.0, 1.0 - 1.6 * (s - 0.5), 0.1, 0.9) }
}

fn point_colour(s: PointState) -> Color {
    match s {
        PointState::Stuck => rgba(0.13, 0.40, 0.67, 1.0),
        PointState::Slipping => rgba(0.95, 0.56, 0.0, 1.0),
        PointState::Tip => rgba(0.91, 0.16, 0.54, 1.0),
        PointState::Other => rgba(0.6, 0.6, 0.6, 1.0),
    }
}

fn entity(id: &str, time_ns: u64) -> SceneEntity {
    SceneEntity {
        timestamp: Some(timestamp(time_ns)),
        frame_id: FRAME_ID.to_owned(),
        id: id.to_owned(),
        lifetime: Some(Duration::new(0, 0)),
        ..Default::default()
    }
}

/// The scene of one state: `tissue` (when `surface` is given: the first message of a stream, or
/// every message when displacements are sent), `needle`, `contacts`, `targets`. The colour scale's
/// top is `displacement_scale_m` (≤ 0: the largest displacement shown).
///
/// Each entity replaces the previous one with the same id (Foxglove's rule for scene entities), so
/// a stream can send the surface once and the rest every frame.
pub fn scene_update(surface: Option<&Surface>, f: &SceneFrame<'_>, displacement_scale_m: f64) -> SceneUpdate {
    let mut entities = Vec::with_capacity(4);
    if let Some(s) = surface {
        let mut tissue = entity("tissue", f.time_ns);
        let u = f.surface_displacement_m.filter(|u| u.len() == s.positions_m.len());
        let points: Vec<Point3> = match u {
            Some(u) => s.positions_m.iter().zip(u).map(|(x, d)| p3([x[0] + d[0], x[1] + d[1], x[2] + d[2]])).collect(),
            None => s.positions_m.iter().copied().map(p3).collect(),
        };
        let colors = match u {
            Some(u) => {
                let mag = |d: &[f64; 3]| (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                let top = if displacement_scale_m > 0.0 { displacement_scale_m } else { u.iter().map(mag).fold(0.0, f64::max) };
                let top = if top > 0.0 { top } else { 1.0 };
                u.iter().map(|d| heat(mag(d) / top)).collect()
            }
            None => Vec::new(),
        };
        tissue.triangles.push(TriangleListPrimitive {
            pose: Some(identity_pose()),
            points,
            color: Some(heat(0.0)),
            colors,
            indices: s.triangles.iter().flatten().copied().collect(),
        });
        entities.push(tissue);
    }
    let mut needle = entity("needle", f.time_ns);
    if f.needle_m.len() >= 2 {
        needle.lines.push(LinePrimitive {
            r#type: LineType::LineStrip as i32,
            pose: Some(identity_pose()),
            thickness: 0.6e-3,
            scale_invariant: false,
            points: f.needle_m.iter().copied().map(p3).collect(),
            color: Some(rgba(0.15, 0.15, 0.15, 1.0)),
            ..Default::default()
        });
    }
    entities.push(needle);
    let mut contacts = entity("contacts", f.time_ns);
    contacts.spheres = f
        .points
        .iter()
        .map(|p| SpherePrimitive {
            pose: Some(at(p.position_m)),
            size: Some(Vector3 { x: 1.2e-3, y: 1.2e-3, z: 1.2e-3 }),
            color: Some(point_colour(p.state)),
        })
        .collect();
    entities.push(contacts);
    let mut targets = entity("targets", f.time_ns);
    targets.spheres = f
        .targets
        .iter()
        .map(|t| SpherePrimitive {
            pose: Some(at(t.centre_m)),
            size: Some(Vector3 { x: 2.0 * t.radius_m, y: 2.0 * t.radius_m, z: 2.0 * t.radius_m }),
            color: Some(if t.hit { rgba(0.11, 0.62, 0.47, 0.7) } else { rgba(0.46, 0.44, 0.70, 0.7) }),
        })
        .collect();
    entities.push(targets);
    SceneUpdate { deletions: Vec::new(), entities }
}

/// A vector in the force sample's JSON.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct Vec3Json {
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

impl From<[f64; 3]> for Vec3Json {
    fn from([x, y, z]: [f64; 3]) -> Self {
        Self { x, y, z }
    }
}

/// One tick's base force and torque for Foxglove's Plot panel (message paths such as
/// `/needlesim/<session>/force.force_n.x`).
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct ForceSample {
    /// Simulation time (s).
    pub time_s: f64,
    /// Inserted depth (m).
    pub depth_m: f64,
    /// The tissue's force on the needle base (N, world frame).
    pub force_n: Vec3Json,
    /// Its torque about the base (N·m, world frame).
    pub torque_nm: Vec3Json,
}

impl ForceSample {
    /// The JSON message (UTF-8).
    pub fn to_json(&self) -> Vec<u8> {
        // Serialising plain numbers cannot fail (non-finite values become null).
        serde_json::to_vec(self).unwrap_or_default()
    }
}

/// The force sample's schema name.
pub const FORCE_SCHEMA_NAME: &str = "needlesim.ForceSample";

/// The force sample's JSON Schema (Foxglove's `jsonschema` encoding).
pub const FORCE_SCHEMA_JSON: &str = r#"{
  "title": "needlesim.ForceSample",
  "description": "The tissue's force and torque on the needle base, world frame",
  "type": "object",
  "properties": {
    "time_s": {"type": "number", "description": "simulation time (s)"},
    "depth_m": {"type": "number", "description": "inserted depth (m)"},
    "force_n": {"type": "object", "description": "force (N)", "properties": {"x": {"type": "number"}, "y": {"type": "number"}, "z": {"type": "number"}}},
    "torque_nm": {"type": "object", "description": "torque about the base (N·m)", "properties": {"x": {"type": "number"}, "y": {"type": "number"}, "z": {"type": "number"}}}
  }
}"#;

#[cfg(test)]
mod tests {
    use super::*;
    use prost::Message;

    fn cube_surface() -> Surface {
        // Two triangles of a unit square at z = 0.
        Surface {
            positions_m: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        }
    }

    #[test]
    fn the_surface_moves_with_its_displacements_and_is_coloured_by_their_magnitude() {
        let s = cube_surface();
        let u = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.5], [0.0, 0.0, 1.0], [0.0, 0.0, 0.0]];
        let f = SceneFrame { time_ns: 1_500_000_000, surface_displacement_m: Some(&u), needle_m: &[], points: &[], targets: &[] };
        let up = scene_update(Some(&s), &f, 0.0);
        let tissue = &up.entities[0];
        assert_eq!(tissue.id, "tissue");
        assert_eq!(tissue.timestamp, Some(Timestamp::new(1, 500_000_000)));
        let tri = &tissue.triangles[0];
        assert_eq!(tri.indices, vec![0, 1, 2, 0, 2, 3]);
        assert_eq!(tri.points[2], Point3 { x: 1.0, y: 1.0, z: 1.0 });
        assert_eq!(tri.points[1], Point3 { x: 1.0, y: 0.0, z: 0.5 });
        // Largest displacement: the top of the scale (red); none: white.
        assert_eq!(tri.colors[2], heat(1.0));
        assert_eq!(tri.colors[0], heat(0.0));
        assert!(tri.colors[2].g < 0.25 && tri.colors[0].b > 0.99);
        // A wrong-length displacement is not applied.
        let short = [[0.0, 0.0, 9.0]];
        let f2 = SceneFrame { surface_displacement_m: Some(&short), ..f };
        assert_eq!(scene_update(Some(&s), &f2, 0.0).entities[0].triangles[0].points[0], Point3 { x: 0.0, y: 0.0, z: 0.0 });
    }

    #[test]
    fn needle_contacts_and_targets_are_entities_in_the_tissue_frame_and_survive_protobuf() {
        let needle = [[0.0, 0.0, 0.1], [0.0, 0.0, 0.05]];
        let points = [
            ScenePoint { position_m: [0.0, 0.0, 0.06], state: PointState::Stuck },
            ScenePoint { position_m: [0.0, 0.0, 0.05], state: PointState::Tip },
        ];
        let targets = [SceneTarget { centre_m: [0.0, 0.01, 0.03], radius_m: 2e-3, hit: false }];
        let f = SceneFrame { time_ns: 7, surface_displacement_m: None, needle_m: &needle, points: &points, targets: &targets };
        let up = scene_update(None, &f, 1e-3);
        let ids: Vec<&str> = up.entities.iter().map(|e| e.id.as_str()).collect();
        assert_eq!(ids, ["needle", "contacts", "targets"]);
        assert!(up.entities.iter().all(|e| e.frame_id == FRAME_ID));
        assert_eq!(up.entities[0].lines[0].points.len(), 2);
        assert_eq!(up.entities[1].spheres.len(), 2);
        assert_ne!(up.entities[1].spheres[0].color, up.entities[1].spheres[1].color);
        let t = &up.entities[2].spheres[0];
        assert_eq!(t.size.unwrap().x, 4e-3);
        assert_eq!(t.pose.unwrap().position.unwrap().y, 0.01);
        let bytes = up.encode_to_vec();
        assert_eq!(SceneUpdate::decode(bytes.as_slice()).unwrap(), up);
    }

    #[test]
    fn the_force_sample_is_json_with_the_documented_fields() {
        let s = ForceSample { time_s: 0.5, depth_m: 0.01, force_n: [1.0, -2.0, 0.25].into(), torque_nm: [0.0, 0.001, 0.0].into() };
        let v: serde_json::Value = serde_json::from_slice(&s.to_json()).unwrap();
        assert_eq!(v["force_n"]["y"], -2.0);
        assert_eq!(v["torque_nm"]["y"], 0.001);
        let schema: serde_json::Value = serde_json::from_str(FORCE_SCHEMA_JSON).unwrap();
        for k in v.as_object().unwrap().keys() {
            assert!(schema["properties"].get(k).is_some(), "{k} is not in the schema");
        }
    }
}
