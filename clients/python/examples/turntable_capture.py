#!/usr/bin/env python3
"""Turntable capture: a glTF model turned step by step about the vertical axis, one quilt captured per step.

    holotrace-python turntable_capture.py --target unix:/run/holotrace/holotraced.sock \\
        --model chair.glb --display builtin:portrait --steps 36 --name chair

The model (a local .glb/.gltf; without --model a small demo model) is uploaded to the daemon; its node (--node, else
the first one) gets the world matrix rotation_y(360 deg * i / steps) at step i, and Capture writes that step's views as
one quilt under the daemon's output root: NAME_sNNN_f0000_qs{cols}x{rows}a{aspect}.png plus its .json metadata
(a lenticular display's vendor quilt cameras, a capture grid's cameras). The files form a quilt sequence ready for
the vendor's players or `holotrace interleave`. Progress is printed as each file completes.
"""

import argparse
import math
import os
import sys

from holotrace_client import Client, HolotraceError, rotation_y

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from demo_model import demo_glb  # noqa: E402


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--target", default=None, help="daemon address, unix:/path or host:port "
                        "(default: $HOLOTRACE_TARGET or the daemon's default socket)")
    parser.add_argument("--model", help="local .glb or .gltf (embedded buffers) to upload; default: a demo model")
    parser.add_argument("--node", help="node to turn (default: the model's first node)")
    parser.add_argument("--display", default="builtin:portrait", help="display id (see `holotrace client displays`)")
    parser.add_argument("--steps", type=int, default=36, help="turntable steps over 360 degrees (default 36)")
    parser.add_argument("--name", default="turntable", help="capture name: files NAME_sNNN_f0000_qs...png")
    parser.add_argument("--spp", type=int, default=0, help="samples per pixel (0 = the display's default)")
    args = parser.parse_args(argv)
    if args.steps < 1:
        parser.error("--steps must be >= 1")
    return args


def main(argv=None):
    args = parse_args(argv)
    with Client(args.target) as hc:
        display = hc.display(args.display)
        if display.model == "lenticular":
            quilt = True   # the display's vendor quilt cameras
        elif display.views > 1:
            quilt = False  # a multi-view display whose views are the quilt (capture grid, oblique)
        else:
            print(f"turntable_capture: display '{display.id}' ({display.model}) has a single view, so there is no "
                  "quilt to capture; choose a lenticular or multi-view display", file=sys.stderr)
            return 2
        scene = hc.upload_scene(args.model) if args.model else hc.upload_scene(demo_glb(), "demo_model.glb")
        node = args.node or (scene.nodes[0] if scene.nodes else None)
        if node not in scene.nodes:
            print(f"turntable_capture: no node {node!r} in the model (it has: {', '.join(scene.nodes) or 'none'})",
                  file=sys.stderr)
            return 2
        print(f"{scene.triangles} triangles; turning node '{node}' in {args.steps} steps on '{display.id}'")
        files = []
        for step in range(args.steps):
            hc.update_scene(scene, nodes={node: rotation_y(2.0 * math.pi * step / args.steps)})

            def progress(p, step=step):
                if p.file.endswith(".png"):
                    print(f"  step {step + 1}/{args.steps}: {p.file}", flush=True)
                    files.append(p.file)

            hc.capture(scene, display, f"{args.name}_s{step:03d}", frames=1, layout="quilt", quilt=quilt,
                       spp=args.spp, progress=progress)
        print(f"{len(files)} quilts under the daemon's output root")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except HolotraceError as error:
        print(f"turntable_capture: {error}", file=sys.stderr)
        sys.exit(1)
