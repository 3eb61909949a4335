"""tools/check_includes.py: the source tree keeps the module order of docs/architecture.md, and
the check does catch an include that goes against it."""
import pathlib
import subprocess
import sys
import tempfile
import unittest

ROOT = pathlib.Path(__file__).resolve().parents[2]
CHECK = ROOT / 'tools' / 'check_includes.py'


def check(root):
    return subprocess.run([sys.executable, str(CHECK), str(root)], capture_output=True, text=True)


class CheckIncludes(unittest.TestCase):
    def test_the_tree_keeps_the_order(self):
        r = check(ROOT)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)

    def test_an_include_up_the_path_is_caught(self):
        with tempfile.TemporaryDirectory() as d:
            d = pathlib.Path(d)
            (d / 'cmake').mkdir()
            (d / 'cmake' / 'modules.cmake').write_text(
                'gs_module(core DEPS Eigen3::Eigen)\ngs_module(geometry DEPS gs_core)\n'
                'gs_module(sim DEPS gs_geometry)\ngs_module(app DEPS gs_sim)\n'
                'gs_module(shapes DIRS geometry/shapes DEPS gs_sim)\n')
            (d / 'tests').mkdir()
            (d / 'tests' / 'CMakeLists.txt').write_text('gs_test(geometry DEPS gs_geometry)\n')
            for folder, text in {'src/geometry/a.cpp': '#include "core/x.hpp"\n',
                                 'src/geometry/b.hpp': '#include <vector>\n#include "sim/s.hpp"\n',
                                 'src/app/c.cpp': '#include "geometry/b.hpp"\n',
                                 # a folder of its own module (DIRS) may use what that module links
                                 'src/geometry/shapes/d.cpp': '#include "sim/s.hpp"\n',
                                 'tests/geometry/t.cpp': '#include "app/c.hpp"\n'}.items():
                (d / folder).parent.mkdir(parents=True, exist_ok=True)
                (d / folder).write_text(text)
            r = check(d)
            self.assertEqual(r.returncode, 1)
            self.assertIn('src/geometry/b.hpp:2: geometry includes sim/', r.stdout)
            self.assertIn('tests/geometry/t.cpp:1: geometry includes app/', r.stdout)
            self.assertNotIn('a.cpp', r.stdout)
            self.assertNotIn('c.cpp', r.stdout)
            self.assertNotIn('d.cpp', r.stdout)

    def test_measure_may_not_use_output(self):
        # the real module graph: observers hand rows to a RecordSink, output/ writes them
        with tempfile.TemporaryDirectory() as d:
            d = pathlib.Path(d)
            for f in ('cmake/modules.cmake', 'tests/CMakeLists.txt'):
                (d / f).parent.mkdir(parents=True, exist_ok=True)
                (d / f).write_text((ROOT / f).read_text())
            for f, text in {'src/measure/a.cpp': '#include "output/csv.hpp"\n',
                            'src/measure/b.cpp': '#include "core/records.hpp"\n',
                            'src/sim/c.cpp': '#include "output/run_dir.hpp"\n'}.items():
                (d / f).parent.mkdir(parents=True, exist_ok=True)
                (d / f).write_text(text)
            r = check(d)
            self.assertEqual(r.returncode, 1)
            self.assertIn('src/measure/a.cpp:1: measure includes output/', r.stdout)
            self.assertIn('src/sim/c.cpp:1: sim includes output/', r.stdout)
            self.assertNotIn('b.cpp', r.stdout)


if __name__ == '__main__':
    unittest.main()
