#!/usr/bin/env python3
"""Generates the Python gRPC stubs of needlesim.v1 (needlesim/v1/needlesim_pb2{,_grpc}.py).

usage: generate.py OUT_DIR

Runs `python -m grpc_tools.protoc -I proto --python_out=OUT --grpc_python_out=OUT
proto/needlesim/v1/*.proto` from the repository root (one module pair per file). The generated code is not committed:
put OUT_DIR on PYTHONPATH (or pass it as `needlesim_client.py --stubs OUT_DIR`).
"""

import os
import subprocess
import sys

REPO = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
PROTO_DIR = os.path.join("needlesim", "v1")


def generate(out_dir: str) -> None:
    """Writes the stubs into out_dir (created if needed); raises CalledProcessError on failure."""
    out_dir = os.path.abspath(out_dir)
    os.makedirs(out_dir, exist_ok=True)
    subprocess.run(
        [
            sys.executable,
            "-m",
            "grpc_tools.protoc",
            "-I",
            "proto",
            f"--python_out={out_dir}",
            f"--grpc_python_out={out_dir}",
            *sorted(
                os.path.join("proto", PROTO_DIR, name)
                for name in os.listdir(os.path.join(REPO, "proto", PROTO_DIR))
                if name.endswith(".proto")
            ),
        ],
        cwd=REPO,
        check=True,
    )


def main() -> int:
    if len(sys.argv) != 2 or sys.argv[1].startswith("-"):
        print(__doc__, file=sys.stderr)
        return 2
    generate(sys.argv[1])
    print(f"generated {os.path.join(sys.argv[1], 'needlesim', 'v1')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
