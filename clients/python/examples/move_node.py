#!/usr/bin/env python3
"""Move a scene node from a script and see the frame change.

    holotrace-python move_node.py --target unix:/run/holotrace/holotraced.sock \\
        --scene builtin:showcase --display builtin:portrait --node glass-sphere --to 0.3,0.2,0.1 --out moved

Loads the scene, lists its movable nodes, renders a frame, sets the node's world matrix to a translation (UpdateScene:
the edit belongs to this session only, other clients of the same scene keep theirs), renders again and reports how
much of the frame changed. --out PREFIX writes PREFIX_before.png and PREFIX_after.png. An unknown node name is
answered by the daemon with INVALID_ARGUMENT, which arrives here as holotrace_client.InvalidArgument.
"""

import argparse
import sys

import numpy as np

from holotrace_client import Client, HolotraceError, InvalidArgument, translation, write_png


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--target", default=None, help="daemon address, unix:/path or host:port")
    parser.add_argument("--scene", default="builtin:showcase", help="'builtin:NAME' or a path below the scene root")
    parser.add_argument("--display", default="builtin:portrait", help="display id")
    parser.add_argument("--node", help="node to move (default: the scene's first node)")
    parser.add_argument("--to", default="0.3,0.2,0.0", help="new position X,Y,Z in world units")
    parser.add_argument("--spp", type=int, default=1, help="samples per pixel")
    parser.add_argument("--out", help="write OUT_before.png and OUT_after.png")
    args = parser.parse_args(argv)
    try:
        args.position = tuple(float(v) for v in args.to.split(","))
        assert len(args.position) == 3
    except (ValueError, AssertionError):
        parser.error(f"--to wants X,Y,Z, got {args.to!r}")
    return args


def main(argv=None):
    args = parse_args(argv)
    with Client(args.target) as hc:
        scene = hc.load_scene(args.scene)
        print(f"{args.scene}: {scene.triangles} triangles, nodes: {', '.join(scene.nodes) or 'none'}")
        if not scene.nodes:
            print("move_node: this scene has no movable nodes", file=sys.stderr)
            return 2
        node = args.node or scene.nodes[0]
        before = hc.render(scene, args.display, spp=args.spp)
        try:
            update = hc.update_scene(scene, nodes={node: translation(*args.position)})
        except InvalidArgument as error:
            print(f"move_node: the daemon refused the edit: {error.details}", file=sys.stderr)
            return 2
        after = hc.render(scene, args.display, spp=args.spp)
        changed = np.any(before[..., :3] != after[..., :3], axis=-1)
        print(f"moved '{node}' to {args.position}: BVH rebuilt in {update.rebuild_ms:.1f} ms; "
              f"{changed.mean() * 100:.1f} % of the pixels changed, mean |difference| "
              f"{np.abs(before[..., :3].astype(int) - after[..., :3]).mean():.2f} / 255")
        if args.out:
            write_png(f"{args.out}_before.png", before[before.shape[0] // 2])
            write_png(f"{args.out}_after.png", after[after.shape[0] // 2])
            print(f"wrote {args.out}_before.png and {args.out}_after.png")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except HolotraceError as error:
        print(f"move_node: {error}", file=sys.stderr)
        sys.exit(1)
