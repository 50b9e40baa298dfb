//! Foxglove's channels in an MCAP recording: the scene (`foxglove.SceneUpdate`, protobuf, with its
//! descriptor from the SDK) and the force sample (JSON with its JSON Schema), registered on the
//! recording's own writer beside the project's frame channel.
use std::collections::BTreeMap;
use std::io::{Seek, Write};

use foxglove::Encode;
use foxglove::messages::SceneUpdate;
use mcap::records::MessageHeader;
use prost::Message;

use crate::scene::{FORCE_SCHEMA_JSON, FORCE_SCHEMA_NAME, ForceSample};
use crate::{force_topic, scene_topic};

/// The two channels of a session in one MCAP file, and their sequence counters.
#[derive(Debug)]
pub struct McapChannels {
    scene: u16,
    force: u16,
    scene_seq: u32,
    force_seq: u32,
}

impl McapChannels {
    /// Adds the schemas and channels of `session` to `writer`.
    ///
    /// Errors: those of the writer (an I/O error, a writer already finished).
    pub fn register<W: Write + Seek>(writer: &mut mcap::Writer<W>, session: &str) -> Result<Self, mcap::McapError> {
        // The SDK always describes its well-known types; an absent schema would be its bug.
        let schema = <SceneUpdate as Encode>::get_schema().ok_or(mcap::McapError::UnexpectedEof)?;
        let scene_schema = writer.add_schema(&schema.name, &schema.encoding, &schema.data)?;
        let scene = writer.add_channel(scene_schema, &scene_topic(session), "protobuf", &BTreeMap::new())?;
        let force_schema = writer.add_schema(FORCE_SCHEMA_NAME, "jsonschema", FORCE_SCHEMA_JSON.as_bytes())?;
        let force = writer.add_channel(force_schema, &force_topic(session), "json", &BTreeMap::new())?;
        Ok(Self { scene, force, scene_seq: 0, force_seq: 0 })
    }

    /// Writes a scene update at `time_ns` (log and publish time).
    pub fn write_scene<W: Write + Seek>(
        &mut self,
        writer: &mut mcap::Writer<W>,
        time_ns: u64,
        update: &SceneUpdate,
    ) -> Result<(), mcap::McapError> {
        self.write_scene_encoded(writer, time_ns, &update.encode_to_vec())
    }

    /// Writes an already encoded `foxglove.SceneUpdate` (e.g. built on another thread).
    pub fn write_scene_encoded<W: Write + Seek>(
        &mut self,
        writer: &mut mcap::Writer<W>,
        time_ns: u64,
        data: &[u8],
    ) -> Result<(), mcap::McapError> {
        self.scene_seq = self.scene_seq.wrapping_add(1);
        let header = MessageHeader { channel_id: self.scene, sequence: self.scene_seq, log_time: time_ns, publish_time: time_ns };
        writer.write_to_known_channel(&header, data)
    }

    /// Writes a force sample at `time_ns`.
    pub fn write_force<W: Write + Seek>(
        &mut self,
        writer: &mut mcap::Writer<W>,
        time_ns: u64,
        sample: &ForceSample,
    ) -> Result<(), mcap::McapError> {
        self.write_force_encoded(writer, time_ns, &sample.to_json())
    }

    /// Writes an already encoded force sample (JSON).
    pub fn write_force_encoded<W: Write + Seek>(
        &mut self,
        writer: &mut mcap::Writer<W>,
        time_ns: u64,
        data: &[u8],
    ) -> Result<(), mcap::McapError> {
        self.force_seq = self.force_seq.wrapping_add(1);
        let header = MessageHeader { channel_id: self.force, sequence: self.force_seq, log_time: time_ns, publish_time: time_ns };
        writer.write_to_known_channel(&header, data)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{SceneFrame, Surface, scene_update};

    #[test]
    fn a_recording_holds_the_scene_in_foxgloves_schema_and_the_force_as_json() {
        let mut buf = std::io::Cursor::new(Vec::new());
        {
            let mut w = mcap::Writer::new(&mut buf).unwrap();
            let mut ch = McapChannels::register(&mut w, "s1").unwrap();
            let surface = Surface { positions_m: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], triangles: vec![[0, 1, 2]] };
            let needle = [[0.0, 0.0, 1.0], [0.0, 0.0, 0.5]];
            let f = SceneFrame { time_ns: 1000, surface_displacement_m: None, needle_m: &needle, points: &[], targets: &[] };
            ch.write_scene(&mut w, 1000, &scene_update(Some(&surface), &f, 0.0)).unwrap();
            let s = ForceSample { time_s: 1e-6, depth_m: 0.0, force_n: [0.0, 0.0, -1.0].into(), torque_nm: [0.0; 3].into() };
            ch.write_force(&mut w, 1000, &s).unwrap();
            w.finish().unwrap();
        }
        let bytes = buf.into_inner();
        let mut topics = Vec::new();
        for m in mcap::MessageStream::new(&bytes).unwrap() {
            let m = m.unwrap();
            let schema = m.channel.schema.as_ref().unwrap();
            topics.push((m.channel.topic.clone(), schema.name.clone(), m.channel.message_encoding.clone()));
            if schema.name == "foxglove.SceneUpdate" {
                let up = SceneUpdate::decode(&m.data[..]).unwrap();
                assert_eq!(up.entities[0].id, "tissue");
                assert_eq!(up.entities[1].lines[0].points.len(), 2);
            } else {
                let v: serde_json::Value = serde_json::from_slice(&m.data).unwrap();
                assert_eq!(v["force_n"]["z"], -1.0);
            }
        }
        assert_eq!(
            topics,
            [
                ("/needlesim/s1/scene".to_owned(), "foxglove.SceneUpdate".to_owned(), "protobuf".to_owned()),
                ("/needlesim/s1/force".to_owned(), FORCE_SCHEMA_NAME.to_owned(), "json".to_owned()),
            ]
        );
    }
}
