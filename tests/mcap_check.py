#!/usr/bin/env python3
"""Checks an MCAP recording of needlesim with the Python `mcap` package and prints a JSON summary.

usage: mcap_check.py FILE.mcap [--tolerate-truncation]

Prints {"file", "messages", "topics", "schema_names", "schema_encodings", "message_encodings",
"first_sequence", "last_sequence", "in_order", "truncated", "foxglove"}: messages, sequences and
order are those of the project's frame topic (/needlesim/frames); topics and schemas cover every
channel; "foxglove" counts the messages of Foxglove's channels ({"scene", "force"}) and lists the
scene entity ids found by decoding the foxglove.SceneUpdate messages with the descriptor the file
carries ("scene_entities"), and the force sample keys ("force_keys"); "tissue" describes the
tissue messages (/needlesim/tissue: a 2D mesh or a 3D surface, decoded the same way: their
schema, count, nodes and triangles); "displacement_frames" counts the frames carrying a
displacement field and "displacement_lengths" lists the field lengths found.

Without --tolerate-truncation the file is read with `mcap.reader.make_reader` (a seeking reader
that uses the summary): an unfinished file is an error (exit status 1). With
--tolerate-truncation it is read front to back with the non-seeking (streaming) reader, which
reads every complete chunk and stops cleanly at a truncated end ("truncated": true).
"""

import argparse
import json
import sys

from mcap.exceptions import EndOfFile, McapError
from mcap.reader import NonSeekingReader, make_reader


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("file")
    parser.add_argument(
        "--tolerate-truncation",
        action="store_true",
        help="read with the streaming reader and stop cleanly at a truncated end",
    )
    args = parser.parse_args()

    count = 0
    topics, schema_names, schema_encodings, message_encodings = set(), set(), set(), set()
    first_seq = last_seq = None
    in_order = True
    truncated = False
    last_time = None

    foxglove = {"scene": 0, "force": 0, "scene_entities": set(), "force_keys": set()}
    tissue = {"schemas": set(), "count": 0, "nodes": None, "triangles": None}
    displacement_frames, displacement_lengths = 0, set()
    scene_classes = {}

    def scene_class(schema):
        # The message class of a schema (foxglove.SceneUpdate, needlesim.v1.*) from the
        # FileDescriptorSet in the file.
        if schema.id not in scene_classes:
            from google.protobuf import descriptor_pb2, descriptor_pool, message_factory

            fds = descriptor_pb2.FileDescriptorSet.FromString(schema.data)
            pool = descriptor_pool.DescriptorPool()
            for fd in fds.file:
                pool.Add(fd)
            scene_classes[schema.id] = message_factory.GetMessageClass(pool.FindMessageTypeByName(schema.name))
        return scene_classes[schema.id]

    def add(schema, channel, message):
        nonlocal count, first_seq, last_seq, in_order, last_time, displacement_frames
        topics.add(channel.topic)
        message_encodings.add(channel.message_encoding)
        if schema is not None:
            schema_names.add(schema.name)
            schema_encodings.add(schema.encoding)
        if schema is not None and schema.name == "foxglove.SceneUpdate":
            foxglove["scene"] += 1
            for e in scene_class(schema).FromString(message.data).entities:
                foxglove["scene_entities"].add(e.id)
            return
        if schema is not None and schema.name == "needlesim.ForceSample":
            foxglove["force"] += 1
            foxglove["force_keys"].update(json.loads(message.data).keys())
            return
        if schema is not None and schema.name in ("needlesim.v1.Mesh", "needlesim.v1.Surface"):
            m = scene_class(schema).FromString(message.data)
            tissue["schemas"].add(schema.name)
            tissue["count"] += 1
            if schema.name == "needlesim.v1.Mesh":
                tissue["nodes"], tissue["triangles"] = len(m.node_xy_m) // 2, len(m.triangle_nodes) // 3
            else:
                tissue["nodes"], tissue["triangles"] = len(m.node_ids), len(m.triangles) // 3
            return
        if schema is not None and schema.name == "needlesim.v1.Frame":
            f = scene_class(schema).FromString(message.data)
            n = len(f.node_displacement_m) or len(f.surface_displacement_m)
            if n:
                displacement_frames += 1
                displacement_lengths.add(n)
        count += 1
        if first_seq is None:
            first_seq = message.sequence
        elif message.sequence <= last_seq or message.log_time < last_time:
            in_order = False
        last_seq = message.sequence
        last_time = message.log_time

    with open(args.file, "rb") as stream:
        if args.tolerate_truncation:
            reader = NonSeekingReader(stream)
            try:
                for schema, channel, message in reader.iter_messages(log_time_order=False):
                    add(schema, channel, message)
            except (EndOfFile, McapError, EOFError) as e:
                # A killed writer leaves a partial last record (or no footer): stop there.
                truncated = True
                print(f"mcap_check: stopped at a truncated end: {type(e).__name__}: {e}", file=sys.stderr)
        else:
            try:
                reader = make_reader(stream)
                for schema, channel, message in reader.iter_messages():
                    add(schema, channel, message)
            except (EndOfFile, McapError, EOFError) as e:
                print(f"mcap_check: {args.file}: {type(e).__name__}: {e}", file=sys.stderr)
                return 1

    print(
        json.dumps(
            {
                "file": args.file,
                "messages": count,
                "topics": sorted(topics),
                "schema_names": sorted(schema_names),
                "schema_encodings": sorted(schema_encodings),
                "message_encodings": sorted(message_encodings),
                "first_sequence": first_seq,
                "last_sequence": last_seq,
                "in_order": in_order,
                "truncated": truncated,
                "foxglove": {k: sorted(v) if isinstance(v, set) else v for k, v in foxglove.items()},
                "tissue": {k: sorted(v) if isinstance(v, set) else v for k, v in tissue.items()},
                "displacement_frames": displacement_frames,
                "displacement_lengths": sorted(displacement_lengths),
            }
        )
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
