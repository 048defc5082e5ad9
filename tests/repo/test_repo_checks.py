"""test_repo_checks.py - the repository checks find what they must on small synthetic trees (ctest RepoChecksSelfTest).

Run: python3 -B -m unittest test_repo_checks (from tests/repo/).
"""
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_doc_references  # noqa: E402
import check_module_boundaries  # noqa: E402


class Tree:
    """A temporary directory tree (not a git checkout, so every file is scanned)."""

    def __init__(self, files):
        self.dir = tempfile.TemporaryDirectory()
        for path, text in files.items():
            full = os.path.join(self.dir.name, path)
            os.makedirs(os.path.dirname(full), exist_ok=True)
            with open(full, "w", encoding="utf-8") as f:
                f.write(text)

    def __enter__(self):
        return self.dir.name

    def __exit__(self, *exc):
        self.dir.cleanup()


OPTICS = "# Optics\n\n## 2. Raw values\n\n### 4.1 Tiles\n\n## 9. Camera models\n\n## 6. Pitfalls\n\n- **P7 JIT**: x\n"


def messages(root):
    return [(path, message) for path, _, message, _ in check_doc_references.check(root)]


class DocReferences(unittest.TestCase):
    def test_existing_sections_pass(self):
        files = {
            "docs/OPTICS.md": OPTICS,
            "camera_models/a.h": "// docs/OPTICS.md §9 M2, §4.1 and §2 / §9 M1; docs/OPTICS.md §6 P7\n",
            "docs/configs.md": "See [optics](OPTICS.md) and OPTICS.md §2; pbr-book §3.9 is external.\n",
            "configs/x.json": '{"description": "docs/OPTICS.md \\u00a79 M5"}\n',
        }
        with Tree(files) as root:
            self.assertEqual(messages(root), [])

    def test_missing_section_file_case_and_pitfall_fail(self):
        files = {
            "docs/OPTICS.md": OPTICS,
            "a.cpp": "// docs/OPTICS.md §3.2\n// docs/optics.md §2\n// docs/OPTICS.md §6 P8\n",
            "b.json": '{"d": "docs/OPTICS.md \\u00a75"}\n',
            "c.h": "// docs/OPTICS.md §9, §7\n",
        }
        with Tree(files) as root:
            found = messages(root)
        self.assertEqual(len(found), 5, found)
        self.assertTrue(any(p == "a.cpp" and "no heading numbered 3.2" in m for p, m in found))
        self.assertTrue(any(p == "a.cpp" and "docs/optics.md" in m for p, m in found))
        self.assertTrue(any(p == "a.cpp" and "**P8" in m for p, m in found))
        self.assertTrue(any(p == "b.json" and "numbered 5" in m for p, m in found))
        self.assertTrue(any(p == "c.h" and "numbered 7" in m for p, m in found))

    def test_mentions_links_and_machine_paths_fail(self):
        outside = "/" + "work/shared"
        files = {
            "docs/OPTICS.md": OPTICS + "[gone](MISSING.md)\n",
            "README.md": "see docs/NOPE.md and notes.md\n",
            "x.sh": "# from %s/docs/optics.md\n# ../%s\n# /home/%s\n" % (outside, "shared", "someone"),
            "y.md": "external: grpc/grpc doc/naming.md, Src/Renderer/README.md\n",
        }
        with Tree(files) as root:
            found = messages(root)
        self.assertTrue(any(p == "docs/OPTICS.md" and "MISSING.md" in m for p, m in found), found)
        self.assertTrue(any(p == "README.md" and "docs/NOPE.md" in m for p, m in found), found)
        self.assertTrue(any(p == "README.md" and "notes.md" in m for p, m in found), found)
        self.assertGreaterEqual(sum(1 for p, m in found if p == "x.sh" and "outside the repository" in m), 3, found)
        self.assertFalse(any(p == "y.md" for p, m in found), found)

    def test_patches_keep_their_historical_context(self):
        files = {"docs/experiments/x.patch": " // bvh.md §5.2 context line\n"}
        with Tree(files) as root:
            self.assertEqual(messages(root), [])


TOP = "add_library(ht_common INTERFACE)\n"


class ModuleBoundaries(unittest.TestCase):
    def violations(self, files):
        files = dict(files)
        files.setdefault("CMakeLists.txt", TOP)
        with Tree(files) as root:
            violations, _ = check_module_boundaries.check(root)
        return violations

    def test_clean_tree_passes(self):
        files = {
            "gpu/CMakeLists.txt": "add_library(ht_gpu STATIC a.cpp)\ntarget_link_libraries(ht_gpu PUBLIC ht_common)\n",
            "gpu/a.cpp": '#include "common/error.h"\n#include <vulkan/vulkan.h>\n',
            "frame_io/CMakeLists.txt": "add_library(ht_frame_io STATIC f.cpp)\n"
                                       "target_link_libraries(ht_frame_io PRIVATE OpenImageIO::OpenImageIO)\n",
            "frame_io/f.cpp": "#include <OpenImageIO/imageio.h>\n",
            "cli/CMakeLists.txt": "add_library(ht_cli STATIC c.cpp)\ntarget_link_libraries(ht_cli PUBLIC ht_frame_io)\n",
            "tests/CMakeLists.txt": "ht_add_test(T SOURCES t.cpp LIBS ht_cli embree LABELS fast)\n",
            "tests/t.cpp": "#include <embree3/rtcore.h>\n",
        }
        self.assertEqual(self.violations(files), [])

    def test_app_to_app_include_and_link_fail(self):
        files = {
            "cli/CMakeLists.txt": "add_library(ht_cli_image STATIC i.cpp)\n",
            "server/CMakeLists.txt": "add_library(ht_server STATIC s.cpp)\n"
                                     "target_link_libraries(ht_server\n  PRIVATE ht_cli_image)  # reuse\n",
            "server/s.cpp": '#include "cli/srgb.h"\n',
            "cli/i.cpp": '  #  include "server/errors.h"\n',
        }
        found = self.violations(files)
        self.assertIn("link ht_server (server) -> ht_cli_image (cli): app server links app cli", found)
        self.assertIn("include server/s.cpp -> cli/srgb.h: app server includes app cli", found)
        self.assertIn("include cli/i.cpp -> server/errors.h: app cli includes app server", found)

    def test_core_dependencies_fail_also_through_variables_and_transitively(self):
        files = {
            "scene/CMakeLists.txt": "set(_libs ht_helper)\nadd_library(ht_scene STATIC s.cpp)\n"
                                    "target_link_libraries(ht_scene PUBLIC ${_libs})\n",
            "scene/s.cpp": "#include <grpcpp/grpcpp.h>\n#include <mpi.h>\n",
            "helper/CMakeLists.txt": "add_library(ht_helper STATIC h.cpp)\n"
                                     "target_link_libraries(ht_helper PRIVATE PkgConfig::LIBUSB)\n",
            "bvh/CMakeLists.txt": "add_library(ht_bvh STATIC b.cpp)\ntarget_link_libraries(ht_bvh PRIVATE ht_server)\n",
            "bvh/b.h": '#include "frame_io/png.h"\n',
            "server/CMakeLists.txt": "add_library(ht_server STATIC x.cpp)\n",
        }
        found = self.violations(files)
        self.assertIn("include scene/s.cpp -> grpcpp/grpcpp.h: core library scene uses gRPC", found)
        self.assertIn("include scene/s.cpp -> mpi.h: core library scene uses MPI", found)
        self.assertIn("link ht_scene (scene) -> PkgConfig::LIBUSB via ht_helper: core library uses libusb", found)
        self.assertIn("link ht_bvh (bvh) -> ht_server (server) via ht_bvh: core library depends on server", found)
        self.assertIn("include bvh/b.h -> frame_io/png.h: core library bvh includes frame_io", found)

    def test_core_layers_fail_upward_includes(self):
        files = {
            "camera_models/CMakeLists.txt": "add_library(ht_camera_models STATIC m.cpp)\n",
            "camera_models/m.h": '#include "scene/scene.h"\n#include "common/bounds3.h"\n',
            "scene/s.cpp": '#include "gpu/renderer.h"\n',
            "gpu/g.cpp": '#include "scene/scene.h"\n#include "camera_models/m.h"\n#include "bvh/bvh.h"\n',
        }
        found = self.violations(files)
        self.assertIn("include camera_models/m.h -> scene/scene.h: core library camera_models includes scene "
                      "(it may include common)", found)
        self.assertIn("include scene/s.cpp -> gpu/renderer.h: core library scene includes gpu (it may include common)",
                      found)
        self.assertEqual(len(found), 2, found)

    def test_openimageio_and_embree_outside_their_modules_fail(self):
        files = {
            "cli/CMakeLists.txt": "add_library(ht_cli STATIC c.cpp)\n"
                                  "target_link_libraries(ht_cli PRIVATE OpenImageIO::OpenImageIO embree)\n",
            "cli/c.cpp": "#include <OpenImageIO/imageio.h>\n#include <embree3/rtcore.h>\n",
        }
        found = self.violations(files)
        self.assertIn("link ht_cli (cli) -> OpenImageIO::OpenImageIO: only frame_io, tests use OpenImageIO", found)
        self.assertIn("link ht_cli (cli) -> embree: only tests, bench, tools use Embree", found)
        self.assertIn("include cli/c.cpp -> OpenImageIO/imageio.h: only frame_io, tests use OpenImageIO", found)
        self.assertIn("include cli/c.cpp -> embree3/rtcore.h: only tests, bench, tools use Embree", found)

    def test_libusb_only_in_devices_and_core_never_reaches_devices(self):
        files = {
            "devices/CMakeLists.txt": "add_library(ht_devices STATIC d.cpp)\n"
                                      "target_link_libraries(ht_devices PRIVATE PkgConfig::LIBUSB)\n",
            "devices/d.cpp": "#include <libusb.h>\n",
            "cli/CMakeLists.txt": "add_library(ht_cli STATIC c.cpp)\ntarget_link_libraries(ht_cli PUBLIC ht_devices usb-1.0)\n",
            "cli/c.cpp": "#include <libusb-1.0/libusb.h>\n#include \"devices/device_discovery.h\"\n",
            "gpu/CMakeLists.txt": "add_library(ht_gpu STATIC g.cpp)\ntarget_link_libraries(ht_gpu PRIVATE ht_devices)\n",
        }
        found = self.violations(files)
        self.assertNotIn("link ht_devices (devices) -> PkgConfig::LIBUSB: only devices use libusb", found)
        self.assertFalse([v for v in found if v.startswith("include devices/") or v.startswith("include cli/c.cpp -> devices")])
        self.assertIn("link ht_cli (cli) -> usb-1.0: only devices use libusb", found)
        self.assertIn("include cli/c.cpp -> libusb-1.0/libusb.h: only devices use libusb", found)
        self.assertIn("link ht_gpu (gpu) -> PkgConfig::LIBUSB via ht_devices: core library uses libusb", found)
        self.assertIn("link ht_gpu (gpu) -> ht_devices (devices) via ht_gpu: core library depends on devices", found)
    def test_x11_outside_the_display_sink_fails(self):
        files = {
            "present/CMakeLists.txt": "add_library(ht_present STATIC p.cpp)\n"
                                      "target_link_libraries(ht_present PUBLIC PkgConfig::XCB)\n",
            "present/p.cpp": "#include <xcb/randr.h>\n#include <vulkan/vulkan_xcb.h>\n",
            "gpu/CMakeLists.txt": "add_library(ht_gpu STATIC g.cpp)\ntarget_link_libraries(ht_gpu PUBLIC ht_present)\n",
            "gpu/g.cpp": "#include <vulkan/vulkan_xcb.h>\n",
            "server/CMakeLists.txt": "add_library(ht_server STATIC s.cpp)\n"
                                     "target_link_libraries(ht_server PUBLIC ht_present PkgConfig::XCB)\n",
            "server/s.cpp": '#include "present/edid.h"\n',
        }
        found = self.violations(files)
        self.assertFalse([v for v in found if v.startswith(("include present/", "link ht_present"))], found)
        self.assertIn("include gpu/g.cpp -> vulkan/vulkan_xcb.h: core library gpu uses X11", found)
        self.assertIn("link ht_gpu (gpu) -> ht_present (present) via ht_gpu: core library depends on present", found)
        self.assertIn("link ht_gpu (gpu) -> PkgConfig::XCB via ht_present: core library uses X11", found)
        self.assertIn("link ht_server (server) -> PkgConfig::XCB: only present, tests, bench use X11", found)


if __name__ == "__main__":
    unittest.main()
