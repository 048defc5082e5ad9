#!/usr/bin/env python3
"""Stream frames into numpy and write them as a video-ready PNG sequence.

    holotrace-python stream_png_sequence.py --target unix:/run/holotrace/holotraced.sock \\
        --scene builtin:showcase --display builtin:portrait --fps 10 --frames 50 --out frames/

StreamFrames renders at --fps; the client keeps only the newest frame (a slow disk never slows the daemon: frames it
could not write in time are skipped and counted). Each frame arrives as a numpy array (views, height, width, 4) and is
written as OUT/frame_00000.png, frame_00001.png ... (8-bit sRGB, all the same size, numbered without gaps), which
ffmpeg turns into a video with the command printed at the end. Multi-view displays write one view (--view, default
the middle one). With --spin NODE the node turns a little after every frame, so the sequence shows motion.
"""

import argparse
import math
import os
import sys
import time

from holotrace_client import Client, HolotraceError, rotation_y, write_png


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--target", default=None, help="daemon address, unix:/path or host:port")
    parser.add_argument("--scene", default="builtin:showcase", help="'builtin:NAME' or a path below the scene root")
    parser.add_argument("--display", default="builtin:portrait", help="display id")
    parser.add_argument("--fps", type=float, default=10.0, help="frames per second asked of the daemon")
    parser.add_argument("--frames", type=int, default=30, help="frames to write")
    parser.add_argument("--spp", type=int, default=0, help="samples per pixel (0 = the display's default)")
    parser.add_argument("--view", type=int, default=None, help="view written for multi-view displays")
    parser.add_argument("--spin", metavar="NODE", help="turn this node by 360/frames degrees after each frame")
    parser.add_argument("--out", default="frames", help="output directory (created)")
    args = parser.parse_args(argv)
    if args.frames < 1 or not args.fps > 0:
        parser.error("--frames must be >= 1 and --fps > 0")
    return args


def main(argv=None):
    args = parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    with Client(args.target) as hc:
        scene = hc.load_scene(args.scene)
        if args.spin and args.spin not in scene.nodes:
            print(f"stream_png_sequence: no node {args.spin!r} (the scene has: {', '.join(scene.nodes) or 'none'})",
                  file=sys.stderr)
            return 2
        start, written, skipped = time.monotonic(), 0, 0
        with hc.stream(scene, args.display, fps=args.fps, spp=args.spp, frames=args.frames) as frames:
            for frame in frames:
                view = frame.views // 2 if args.view is None else args.view
                if not 0 <= view < frame.views:
                    print(f"stream_png_sequence: --view {view} out of 0..{frame.views - 1}", file=sys.stderr)
                    return 2
                path = os.path.join(args.out, f"frame_{written:05d}.png")
                write_png(path, frame.pixels[view, :, :, :3])  # RGB: video encoders ignore alpha
                written += 1
                skipped += frame.skipped + frame.dropped_frames
                if args.spin:
                    hc.update_scene(scene, nodes={args.spin: rotation_y(2.0 * math.pi * written / args.frames)})
                print(f"  {path}  frame {frame.frame_id}  {frame.width}x{frame.height}  "
                      f"render {frame.render_ms:.0f} ms", flush=True)
        seconds = time.monotonic() - start
        print(f"{written} frames in {seconds:.1f} s ({written / seconds:.1f} fps written), {skipped} skipped")
        print(f"video: ffmpeg -framerate {args.fps:g} -i {os.path.join(args.out, 'frame_%05d.png')} "
              "-vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -pix_fmt yuv420p out.mp4")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except HolotraceError as error:
        print(f"stream_png_sequence: {error}", file=sys.stderr)
        sys.exit(1)
