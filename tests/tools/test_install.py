"""`cmake --install` into a temporary prefix: the installed binary, run from another directory,
finds its scenes and shaders under PREFIX/share/gransim and the charts of the gransim Python
package under PREFIX/lib/python3/dist-packages (no source tree needed), renders with OSMesa when
it was built with it, and draws the charts of `analyze`. Usage: test_install.py BUILD_DIR."""
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import unittest

BUILD = pathlib.Path(sys.argv.pop(1) if len(sys.argv) > 1 else 'build').resolve()


def run(args, cwd, **kw):
    env = dict(os.environ, OMP_NUM_THREADS='1')
    env.pop('GS_PYTHON_DIR', None)
    return subprocess.run(args, cwd=cwd, env=env, capture_output=True, text=True, timeout=600, **kw)


def have_matplotlib():
    return subprocess.run(['/usr/bin/python3', '-c', 'import matplotlib'],
                          capture_output=True).returncode == 0


def write_series(d):
    """three φ series of 120 taps and their manifest in folder d"""
    rows = ['file,protocol,control,test_area']
    for k, mean in enumerate((0.835, 0.830, 0.826)):
        lines = ['tap,phi'] + [f'{i + 1},{mean + 0.002 * ((i * 7919 + k) % 11 - 5) / 5:.6f}'
                               for i in range(120)]
        (d / f's{k}.csv').write_text('\n'.join(lines) + '\n')
        rows.append(f's{k}.csv,experiment,{2 * k + 2},0.13')
    (d / 'manifest.csv').write_text('\n'.join(rows) + '\n')


class Install(unittest.TestCase):
    def test_installed_binary_stands_alone(self):
        with tempfile.TemporaryDirectory() as d:
            d = pathlib.Path(d)
            prefix, elsewhere = d / 'prefix', d / 'elsewhere'
            r = run(['cmake', '--install', str(BUILD), '--prefix', str(prefix)], cwd=d)
            self.assertEqual(r.returncode, 0, r.stderr)
            exe = prefix / 'bin' / 'gransim'
            share = prefix / 'share' / 'gransim'
            for sub in ('scenes/demo.toml', 'shaders'):
                self.assertTrue((share / sub).exists(), sub)
            package = prefix / 'lib' / 'python3' / 'dist-packages' / 'gransim'
            for sub in ('__init__.py', 'charts/tapping.py', 'reproduce/__main__.py',
                        'reproduce/verdicts.py'):
                self.assertTrue((package / sub).exists(), sub)
            self.assertFalse((share / 'tools').exists())  # the development tools stay behind
            elsewhere.mkdir()
            version = run([str(exe), '--version'], cwd=elsewhere).stdout
            self.assertIn('gransim', version)
            # the demo scene from the prefix, shortened, written here
            r = run([str(exe), 'run', str(share / 'scenes' / 'demo.toml'), '--out', 'demo',
                     '--set', 'scene.duration=0.2', '-q'], cwd=elsewhere)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            self.assertTrue((elsewhere / 'demo' / 'state.csv').exists())
            r = run([str(exe), 'render', 'demo', '-o', 'pile.png'], cwd=elsewhere)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            self.assertTrue((elsewhere / 'pile.png').stat().st_size > 1000)
            if 'OSMesa' in version:
                # the shaders were found beside the binary: no fall-back to the software rasteriser
                self.assertIn('OSMesa', r.stdout + r.stderr)
            # moved: the prefix copied elsewhere still finds its files relative to itself
            moved = d / 'moved'
            shutil.copytree(prefix, moved, symlinks=True)
            shutil.rmtree(prefix)
            r = run([str(moved / 'bin' / 'gransim'), 'render', 'demo', '-o', 'again.png'],
                    cwd=elsewhere)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            if 'OSMesa' in version:
                self.assertIn('OSMesa', r.stdout + r.stderr)
            # the charts come from the moved prefix's package
            if have_matplotlib():
                write_series(elsewhere)
                r = run([str(moved / 'bin' / 'gransim'), 'analyze', '--manifest', 'manifest.csv',
                         '--out', 'analysis', '-q'], cwd=elsewhere)
                self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
                self.assertNotIn('charts skipped', r.stdout + r.stderr)
                self.assertTrue((elsewhere / 'analysis' / 'fig5_mean_sigma_experiment.png').exists())

    def test_a_build_tree_elsewhere_finds_the_source_package(self):
        # a binary with nothing beside it (as in `cmake -S . -B ../build`) uses the source tree
        # it was built from: the charts of `analyze` are drawn
        if not have_matplotlib():
            self.skipTest('no matplotlib for the charts')
        with tempfile.TemporaryDirectory() as d:
            d = pathlib.Path(d)
            (d / 'bin').mkdir()
            shutil.copy2(BUILD / 'gransim', d / 'bin' / 'gransim')
            write_series(d)
            r = run([str(d / 'bin' / 'gransim'), 'analyze', '--manifest', 'manifest.csv',
                     '--out', 'analysis', '-q'], cwd=d)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            self.assertNotIn('charts skipped', r.stdout + r.stderr)
            self.assertTrue((d / 'analysis' / 'fig5_mean_sigma_experiment.png').exists())


if __name__ == '__main__':
    unittest.main()
