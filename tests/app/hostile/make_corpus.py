#!/usr/bin/env python3
"""Regenerate the hostile corpus: scenes, CSV series, state files and a fixture run directory,
each with one thing broken, and the MANIFEST the test (test_hostile.cpp) reads: one case a line,
file<TAB>class<TAB>expected exit code<TAB>substring of the message<TAB>command. The command's
placeholders are filled in by the test ({file}, {out}, {run}, {locked}, {fifo}, … — see
test_hostile.cpp); "-" as the file: the case has no corpus file of its own."""
import os, re, struct, zlib, shutil

HERE = os.path.dirname(os.path.abspath(__file__))

# a tiny valid scene (10 disks, 1 ms): any file that is accidentally accepted runs fast
BASE = """[scene]
name = "hostile"
duration = 0.001

[model]
kind = "S"

[[material]]
name = "glass"
ks = 5e5
eps_n = 0.6
eps_t = 1.0

[[species]]
name = "bead"
shape = "disk"
radius = 0.0015
mass = 3.53e-5
count = 10

[box]
kind = "periodic"
width = 0.05

[integrator]
kind = "velocity_verlet"
dt = 1e-6

[drive]
kind = "none"
"""

POLY = """[scene]
name = "hostile_poly"
duration = 0.001

[[species]]
name = "big"
sides = 10
radius = 0.009
count = 10

[box]
kind = "walls"
width = 0.2
height = 0.6

[integrator]
kind = "velocity_verlet"
dt = 5e-5
"""

def sub(text, old, new):
    assert old in text, old
    return text.replace(old, new, 1)

CASES = {}  # name -> (bytes, expected substring, exit code, class, command)
RUN = "run {file} --out {out} --quiet"

def case(name, text, expect, code=2, cls="scene", cmd=RUN):
    CASES[name] = (text.encode() if isinstance(text, str) else text, expect, code, cls, cmd)

COMMANDS = []  # (class, exit code, substring, command) of cases without a corpus file

def command(cls, code, expect, cmd):
    COMMANDS.append((cls, code, expect, cmd))

# syntax
case("syntax_unclosed_table.toml", sub(BASE, "[box]", "[box"), ":")
case("syntax_unterminated_string.toml", sub(BASE, 'name = "hostile"', 'name = "hostile'), ":")
case("syntax_duplicate_key.toml", sub(BASE, "width = 0.05", "width = 0.05\nwidth = 0.06"), "width")
case("syntax_garbage.toml", "this is not toml at all\n" + BASE, ":1")
case("syntax_int_overflow.toml", BASE + "\n[preparation]\nseed = 99999999999999999999999\n", ":")
case("syntax_deep_nesting.toml", "x = " + "[" * 5000 + "]" * 5000 + "\n" + BASE, ":")
case("syntax_bad_utf8.toml", sub(BASE, 'name = "hostile"', 'name = "host\xff\xfeile"').encode("latin-1"), ":")
# malformed headers that trip toml++ 3.3 debug asserts (marzer/tomlplusplus#294, #301)
case("syntax_header_ampersand.toml", "[&\n" + BASE, ":1:")
case("syntax_header_triple_bracket.toml", "[[[1]]]\n" + BASE, ":1:")
case("syntax_header_equals.toml", "[[=\n" + BASE, ":1:")
case("syntax_header_paren.toml", sub(BASE, "[drive]", "[)rive]"), "TOML syntax error")
# non-ASCII where toml++ 3.3 checks for whitespace: UB upstream (marzer/tomlplusplus#295)
case("syntax_non_ascii_key.toml", "\u03b5_n = 0.6\n" + BASE, ":1:")
case("syntax_utf8_cc_aa.toml", b"\xcc\xaa", ":1:")
case("empty.toml", "", "species")
case("binary.toml", bytes((i * 97 + 13) % 256 for i in range(512)), ":")
case("only_comments.toml", "# nothing here\n# at all\n", "species")
# wrong types
case("type_radius_string.toml", sub(BASE, "radius = 0.0015", 'radius = "big"'), "radius")
case("type_count_float.toml", sub(BASE, "count = 10", "count = 1e3"), "count")
case("type_kind_number.toml", sub(BASE, 'kind = "periodic"', "kind = 3"), "box.kind")
case("type_lid_string.toml", sub(BASE, "width = 0.05", 'width = 0.05\nlid = "yes"'), "box.lid")
case("type_species_not_array.toml", sub(BASE, "[[species]]", "[species]"), "species")
case("type_test_rect_short.toml", BASE + "\n[output]\ntest_rect = [0.0, 0.0, 1.0]\n", "test_rect")
case("type_box_is_value.toml", sub(sub(BASE, "[box]\n", ""), 'kind = "periodic"\nwidth = 0.05', 'box = 3'), "box")
# unknown names
case("unknown_key.toml", sub(BASE, "radius = 0.0015", "radus = 0.0015"), "radus")
case("unknown_section.toml", BASE + "\n[frobnicate]\nx = 1\n", "frobnicate")
case("unknown_integrator.toml", sub(BASE, 'kind = "velocity_verlet"', 'kind = "rk4"'), "integrator.kind")
case("unknown_material_ref.toml", sub(BASE, 'mass = 3.53e-5', 'mass = 3.53e-5\nmaterial = "steel"'), "material")
case("unknown_particle_species.toml", sub(BASE, "count = 10", "count = 1") +
     '\n[[preparation.particle]]\nspecies = "ghost"\nx = 0.01\ny = 0.01\n', "species")
# missing sections and keys
case("missing_box.toml", re.sub(r"\[box\]\nkind = \"periodic\"\nwidth = 0.05\n", "", BASE), "box")
case("missing_species.toml", re.sub(r"\[\[species\]\][^\[]*", "", BASE), "species")
case("missing_radius.toml", sub(BASE, "radius = 0.0015\n", ""), "radius")
case("missing_count.toml", sub(BASE, "count = 10\n", ""), "count")
case("missing_width.toml", sub(BASE, "width = 0.05\n", ""), "width")
# out-of-range values
case("value_radius_zero.toml", sub(BASE, "radius = 0.0015", "radius = 0.0"), "radius")
case("value_radius_negative.toml", sub(BASE, "radius = 0.0015", "radius = -0.0015"), "radius")
case("value_radius_nan.toml", sub(BASE, "radius = 0.0015", "radius = nan"), "radius")
case("value_mass_inf.toml", sub(BASE, "mass = 3.53e-5", "mass = inf"), "mass")
case("value_dt_zero.toml", sub(BASE, "dt = 1e-6", "dt = 0.0"), "dt")
case("value_dt_negative.toml", sub(BASE, "dt = 1e-6", "dt = -1e-6"), "dt")
case("value_dt_neg_inf.toml", sub(BASE, "dt = 1e-6", "dt = -inf"), "dt")
case("value_sides_two.toml", sub(POLY, "sides = 10", "sides = 2"), "sides")
case("value_sides_huge.toml", sub(POLY, "sides = 10", "sides = 100000"), "sides")
case("value_eps_n_zero.toml", sub(BASE, "eps_n = 0.6", "eps_n = 0.0"), "eps_n")
case("value_eps_n_above_one.toml", sub(BASE, "eps_n = 0.6", "eps_n = 1.5"), "eps_n")
case("value_ks_negative.toml", sub(BASE, "ks = 5e5", "ks = -5e5"), "ks")
case("value_max_overlap.toml", BASE + "\n[health]\nmax_overlap = 2.0\n", "max_overlap")
case("value_check_every_zero.toml", BASE + "\n[health]\ncheck_every = 0\n", "check_every")
case("value_duration_zero.toml", sub(BASE, "duration = 0.001", "duration = 0.0"), "duration")
case("value_count_negative.toml", sub(BASE, "count = 10", "count = -5"), "count")
case("value_count_huge.toml", sub(BASE, "count = 10", "count = 9999999999"), "count")
case("value_count_all_zero.toml", sub(BASE, "count = 10", "count = 0"), "count")
case("value_width_huge.toml", sub(BASE, "width = 0.05", "width = 1e300"), "width")
case("value_radius_huge.toml", sub(BASE, "radius = 0.0015", "radius = 1e300"), "radius")
case("value_gravity_direction_zero.toml", sub(POLY, "dt = 5e-5", "dt = 5e-5\n\n[drive]\nkind = \"gravity\"\ngx = 0.0\ngy = 0.0"), "gx")
case("value_output_series_zero.toml", BASE + "\n[output]\nseries_every = 0\n", "series_every")
case("value_test_rect_inverted.toml", BASE + "\n[output]\ntest_rect = [0.4, 0.0, 0.1, 0.4]\n", "test_rect")
case("value_render_size_zero.toml", BASE + "\n[render]\nsize = [0, 0]\n", "size")
case("value_gr_rmax_too_big.toml", BASE + "\n[rfm]\ngr_rmax = 1.0\n", "gr_rmax")
# geometry that cannot be built
case("too_many_grains_periodic.toml", sub(BASE, "count = 10", "count = 100000"), "fit")
case("too_many_grains_walls.toml", sub(sub(POLY, "count = 10", "count = 5000"), "height = 0.6",
     "height = 0.1") + "\n[preparation]\ncolumn_height = 0.05\n", "fit")
case("particle_outside_box.toml", sub(POLY, "count = 10", "count = 1") +
     "\n[[preparation.particle]]\nx = 5.0\ny = 0.1\n", "preparation.particle[0].x")
case("value_radius_tiny.toml", sub(BASE, "radius = 0.0015", "radius = 1e-300"), "width")
# accepted on purpose (exit code in the third column): explicit particles may overlap
case("particles_overlapping.toml", sub(BASE, "count = 10", "count = 2") +
     "\n[[preparation.particle]]\nx = 0.01\ny = 0.01\n\n[[preparation.particle]]\nx = 0.0105\ny = 0.01\n", "", 0)
# ... but not at one point: their contact would have no direction
case("particles_coincident.toml", sub(BASE, "count = 10", "count = 2") +
     "\n[[preparation.particle]]\nx = 0.01\ny = 0.01\n\n[[preparation.particle]]\nx = 0.01\ny = 0.01\n", "same point")
case("particle_nan.toml", sub(BASE, "count = 10", "count = 1") +
     "\n[[preparation.particle]]\nx = nan\ny = 0.01\n", "x")
case("particle_count_mismatch.toml", sub(BASE, "count = 10", "count = 3") +
     "\n[[preparation.particle]]\nx = 0.01\ny = 0.01\n", "count")
case("duplicate_species_name.toml", BASE.replace("[box]", """[[species]]
name = "bead"
shape = "disk"
radius = 0.001
mass = 1e-5
count = 5

[box]"""), "name")
case("duplicate_material_name.toml", sub(BASE, "[[species]]", '[[material]]\nname = "glass"\n\n[[species]]'), "name")
case("model_s_polygon.toml", sub(BASE, 'shape = "disk"', 'shape = "polygon"'), "shape")
case("ring_polygon.toml", sub(sub(POLY, 'kind = "walls"', 'kind = "ring"'), "height = 0.6\n", ""), "ring")
case("ring_reduced_and_width.toml", sub(sub(BASE, 'kind = "periodic"', 'kind = "ring"'),
     "width = 0.05", "width = 0.05\nreduced_length = 0.01"), "reduced_length")
# stability and protocol
case("dt_too_large.toml", sub(BASE, "dt = 1e-6", "dt = 1e-3"), "dt")
# within 1/5 of the contact time but beyond Gear 6's stability limit (omega*dt 0.42 > 0.35)
case("dt_beyond_gear6_limit.toml", sub(sub(BASE, "dt = 1e-6", "dt = 2.5e-6"),
     'kind = "velocity_verlet"', 'kind = "gear6"'), "stability limit")
case("protocol_t1_ge_period.toml", POLY + '\n[drive]\nkind = "negative_g"\nt1 = 3.0\nperiod = 2.0\ntaps = 2\n', "t1")
case("protocol_taps_with_gravity.toml", POLY + '\n[drive]\nkind = "gravity"\ntaps = 5\n', "taps")
case("protocol_g_p_negative.toml", POLY + '\n[drive]\nkind = "negative_g"\ng_p = -6.0\ntaps = 1\n', "g_p")
case("protocol_f_zero.toml", POLY + '\n[drive]\nkind = "rotating_g"\nf = 0.0\ntaps = 1\n', "drive.f")
case("protocol_random_force_D_zero.toml", sub(BASE, 'kind = "none"', 'kind = "random_force"\nD = 0.0'), "D")
case("protocol_negative_taps.toml", POLY + '\n[drive]\nkind = "negative_g"\ntaps = -1\n', "taps")

# the cases of the other commands (render, movie, analyze, sweep, model, resume) and the fixture
# run directory, kept in a file of their own to keep this one short
exec(open(os.path.join(HERE, "corpus_more.py")).read())

# ---- checkpoints: mutations of a valid seed (fuzz/corpus/checkpoint/pile.gsck) ----
SEED = os.path.join(HERE, "..", "..", "..", "fuzz", "corpus", "checkpoint", "pile.gsck")
CKPT = {}  # name -> (bytes, expected substring, stage: "read" or "restore")

def fnv(b):
    h = 1469598103934665603
    for c in b:
        h = ((h ^ c) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return h

def reseal(b):
    """fix size and checksum after editing the payload"""
    p = bytes(b[32:])
    return bytes(b[:16]) + struct.pack("<QQ", len(p), fnv(p)) + p

def make_checkpoints():
    good = open(SEED, "rb").read()
    scene_len = struct.unpack_from("<Q", good, 32)[0]
    scene = good[40:40 + scene_len]
    after = 40 + scene_len           # clock origin, t, step, n
    n = struct.unpack_from("<Q", good, after + 24)[0]
    sp_at = after + 32
    def ck(name, data, expect, stage="read"):
        CKPT[name] = (data, expect, stage)
    ck("ckpt_empty.gsck", b"", "32-byte header")
    ck("ckpt_text.gsck", b"this is a scene, not a checkpoint\n" * 3, "bad magic")
    ck("ckpt_binary_noise.gsck", bytes((i * 131 + 7) % 256 for i in range(4096)), "bad magic")
    ck("ckpt_header_only.gsck", good[:32], "payload size")
    ck("ckpt_truncated_half.gsck", good[:len(good) // 2], "payload size")
    ck("ckpt_truncated_last_byte.gsck", good[:-1], "payload size")
    ck("ckpt_trailing_garbage.gsck", good + b"\0\0\0\0", "payload size")
    b = bytearray(good); b[len(good) // 2] ^= 0x01
    ck("ckpt_bit_flip.gsck", bytes(b), "checksum mismatch")
    b = bytearray(good); struct.pack_into("<I", b, 8, 99)
    ck("ckpt_wrong_version.gsck", bytes(b), "version 99")
    b = bytearray(good); struct.pack_into(">I", b, 12, 0x01020304)
    ck("ckpt_big_endian.gsck", bytes(b), "big-endian")
    b = bytearray(good); struct.pack_into("<I", b, 12, 0xdeadbeef)
    ck("ckpt_bad_endian_marker.gsck", bytes(b), "endianness marker")
    b = bytearray(good); struct.pack_into("<Q", b, 16, 1 << 62)
    ck("ckpt_huge_size.gsck", bytes(b), "payload size")
    # resealed payload edits: the checksum is right, the contents are not
    b = bytearray(good); struct.pack_into("<Q", b, 32, 1 << 60)
    ck("ckpt_huge_scene_length.gsck", reseal(b), "truncated checkpoint")
    b = bytearray(good); struct.pack_into("<Q", b, after + 24, 1 << 40)
    ck("ckpt_huge_particle_count.gsck", reseal(b), "truncated checkpoint")
    ck("ckpt_payload_cut.gsck", reseal(bytearray(good[:after + 40])), "truncated checkpoint")
    b = bytearray(good); struct.pack_into("<i", b, sp_at, 77)
    ck("ckpt_bad_species.gsck", reseal(b), "unknown species", "restore")
    b = bytearray(good); struct.pack_into("<d", b, after + 8, 1e38)  # found by fuzz_restore
    ck("ckpt_time_not_steps.gsck", reseal(b), "not step", "restore")
    b = bytearray(good); struct.pack_into("<d", b, sp_at + 4 * n, 0.5)  # found by fuzz_restore
    ck("ckpt_grain_not_species.gsck", reseal(b), "not its species", "restore")
    b = bytearray(good); struct.pack_into("<d", b, sp_at + 4 * n + 4 * 8 * n, float("nan"))
    ck("ckpt_nan_position.gsck", reseal(b), "non-finite", "restore")
    bad_scene = scene.replace(b"radius = ", b"radius = -", 1)
    ck("ckpt_bad_embedded_scene.gsck", reseal(bytearray(good[:32] + struct.pack("<Q", len(bad_scene))
       + bad_scene + good[after:])), "radius", "restore")
    other = scene.replace(b'kind = "gear6"', b'kind = "position_verlet"', 1)
    assert other != scene
    ck("ckpt_wrong_integrator.gsck", reseal(bytearray(good[:32] + struct.pack("<Q", len(other))
       + other + good[after:])), "integrator", "restore")

def main():
    make_checkpoints()
    make_more()
    for f in os.listdir(HERE):
        if f.endswith((".toml", ".csv")):
            os.remove(os.path.join(HERE, f))
    make_fixture_run()
    with open(os.path.join(HERE, "MANIFEST"), "w") as m:
        m.write("# file<TAB>class<TAB>exit code<TAB>substring of the message<TAB>command "
                "(make_corpus.py; placeholders: test_hostile.cpp)\n")
        for name, (data, expect, code, cls, cmd) in sorted(CASES.items()):
            with open(os.path.join(HERE, name), "wb") as f:
                f.write(data)
            m.write(f"{name}\t{cls}\t{code}\t{expect}\t{cmd}\n")
        for cls, code, expect, cmd in COMMANDS:
            m.write(f"-\t{cls}\t{code}\t{expect}\t{cmd}\n")
    for f in os.listdir(HERE):
        if f.endswith(".gsck"):
            os.remove(os.path.join(HERE, f))
    with open(os.path.join(HERE, "MANIFEST_CHECKPOINTS"), "w") as m:
        m.write("# checkpoint<TAB>substring of the error<TAB>stage that refuses it (read|restore)\n")
        for name, (data, expect, stage) in sorted(CKPT.items()):
            with open(os.path.join(HERE, name), "wb") as f:
                f.write(data)
            m.write(f"{name}\t{expect}\t{stage}\n")
    print(len(CASES), "files,", len(COMMANDS), "commands,", len(CKPT), "checkpoints")

if __name__ == "__main__":
    main()
