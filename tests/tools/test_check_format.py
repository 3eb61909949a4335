"""tools/check_format.sh: every C++ source is as .clang-format writes it, and the check does catch
a file that is not."""
import pathlib
import shutil
import subprocess
import tempfile
import unittest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def check(root, *args):
    return subprocess.run(['bash', str(root / 'tools' / 'check_format.sh'), *args],
                          capture_output=True, text=True)


class CheckFormat(unittest.TestCase):
    def test_the_tree_is_formatted(self):
        r = check(ROOT)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)

    def test_a_misformatted_file_is_caught_and_fixed(self):
        with tempfile.TemporaryDirectory() as d:
            d = pathlib.Path(d)
            (d / 'tools').mkdir()
            shutil.copy(ROOT / 'tools' / 'check_format.sh', d / 'tools')
            shutil.copy(ROOT / '.clang-format', d)
            for sub in ('src/core', 'tests', 'bench', 'fuzz', 'python'):
                (d / sub).mkdir(parents=True)
            (d / 'src/core/a.cpp').write_text('int f(int x){return x+1;}\n')
            r = check(d)
            self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
            self.assertIn('a.cpp', r.stdout)
            self.assertEqual(check(d, '--fix').returncode, 0)
            self.assertEqual(check(d).returncode, 0)
            self.assertEqual((d / 'src/core/a.cpp').read_text(), 'int f(int x) { return x + 1; }\n')


if __name__ == '__main__':
    unittest.main()
