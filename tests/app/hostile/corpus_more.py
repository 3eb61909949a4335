# the hostile cases beyond `gransim run` on a bad scene, by class (docs/robustness.md):
# 1 concurrent writers, 2 outputs over inputs, 3 derived quantities, 4 hangs and memory,
# 5 bad data and unwritable outputs, 6 truncated and inconsistent files.
# Executed by make_corpus.py (BASE, POLY, sub, case, command come from there).

STATE_HEAD = "# gransim state v1\n# t=0.001 step=1000 n=10\nid,species,x,y,theta,vx,vy,omega\n"

def state_rows(n=10, species="bead"):
    return "".join(f"{i},{species},{0.004 + 0.0045 * i:.4f},0.01,0,0,0,0\n" for i in range(n))

GOOD_STATE = STATE_HEAD + state_rows()

def png(width, height, shade):
    """a tiny grey RGB PNG"""
    raw = b"".join(b"\0" + bytes([shade, shade, shade]) * width for _ in range(height))
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))

def make_fixture_run():
    """a small completed run: what render, movie, sweep and model meet in a run directory"""
    d = os.path.join(HERE, "fixture_run")
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(os.path.join(d, "frames"))
    files = {"scene.toml": BASE, "state.csv": GOOD_STATE,
             "run.json": '{\n  "program": "gransim",\n  "status": "completed"\n}\n',
             "series.csv": "t,step,phi\n0,0,0.5\n0.001,1000,0.5\n"}
    for name, text in files.items():
        with open(os.path.join(d, name), "w") as f:
            f.write(text)
    with open(os.path.join(d, "final.png"), "wb") as f:
        f.write(png(16, 16, 200))
    for k in range(4):
        with open(os.path.join(d, "frames", f"frame_{k:06d}.png"), "wb") as f:
            f.write(png(16, 16, 40 * k))

def make_more():
    R = "{run}"
    SCENE = R + "/scene.toml"
    RENDER = "render {file} --scene " + SCENE + " -o {out}.png"
    SERIES = "analyze --series negative_g:6:{file} --test-area 0.01 --out {out} --no-charts -q"
    WALK = "model walk --paths {file} --walks 20 --radius 0.001 --out {out} --no-charts -q --no-heating"

    # ---- class 1: a second writer while another process holds the directory's lock
    for cmd in ["render {locked} -o {locked}/frame.png", "render {locked}",
                "movie {locked} -o {locked}/movie2.mp4 -q", "run " + "{locked}/scene.toml --out {locked} --force -q",
                "resume {locked_empty} -q",
                "analyze --series negative_g:6:{corpus}/series_good.csv --test-area 0.01 --out {locked_empty} -q",
                "model bisection --realisations 10 --out {locked_empty} --force --no-charts -q",
                "sweep {locked}/scene.toml --param drive.kind=none --out {locked_empty} -q"]:
        command("1-lock", 2, "PID", cmd)

    # ---- class 2: an output that is an input or a file of an existing run
    for out, expect in [("{run}/state.csv", ".png"), ("{run}/final.png", "file of the run"),
                        ("{run}/frames/frame_000000.png", "file of the run"), ("{run}", ".png"),
                        ("{run}/scene.toml", ".png")]:
        command("2-output", 2, expect, "render {run} -o " + out)
    command("2-output", 2, ".png", "render {run}/state.csv -o {run}/state.csv")
    command("2-output", 2, "input", "render {run}/state.csv --scene {tmp}/same.png -o {tmp}/same.png")
    command("2-output", 0, "", "render {run} -o {run}/frame.png")
    command("2-output", 2, ".mp4", "movie {run} -o {run}/series.csv --force -q")
    command("2-output", 2, ".mp4", "movie {run} -o {run}/state.csv --force -q")
    command("2-output", 2, "exists", "movie {run} -o {run}/final.png -q")
    command("2-output", 2, "holds a run", "model bisection --realisations 10 --out {run} --no-charts -q")
    command("2-output", 2, "not empty", "model bisection --realisations 10 --out {nonempty} --no-charts -q")
    command("2-output", 0, "", "model bisection --realisations 10 --out {nonempty} --force --no-charts -q")
    command("2-output", 2, "not a folder", "model interval --walks 10 --out {run}/state.csv --no-charts -q")
    command("2-output", 2, "same run directory", "sweep {run}/scene.toml --param scene.description=\"x\",x --out {out} -q")
    command("2-output", 2, "_rep=N", "sweep {run}/scene.toml --param scene.description=a,a_rep=1 --replicas 2 --out {out} -q")
    command("2-output", 2, "is a file", "resume {run}/state.csv -q")
    command("2-output", 2, "holds a run", "sweep {run}/scene.toml --param drive.kind=none --out {run} -q")
    command("2-output", 2, "not empty", "sweep {run}/scene.toml --param drive.kind=none --out {nonempty} -q")
    command("2-output", 2, "choose another --out", "analyze {run} --out {run} --no-charts -q")
    case("series_good.csv", "tap,phi\n" + "".join(f"{i},{0.8 + 0.001 * (i * 7 % 11)}\n" for i in range(1, 41)),
         "", 2, "2-output", "analyze --series negative_g:6:{file} --test-area 0.01 --out {file} --no-charts -q")
    case("good_base.toml", BASE, "", 0, "2-output", "run {file} --out {out} --quiet")
    case("bad_scene_force.toml", sub(BASE, "radius = 0.0015", "radius = -1"), "radius", 2, "2-output",
         "run {file} --out {run} --force --quiet")

    # ---- class 3: derived quantities out of range, refused before the run
    P = POLY
    case("bounds_test_rect_outside.toml", BASE + "\n[output]\ntest_rect = [1.0, 1.0, 2.0, 2.0]\n", "test_rect", 2, "3-bounds")
    case("bounds_test_rect_partly_outside.toml", BASE + "\n[output]\ntest_rect = [0.01, 0.01, 0.06, 0.04]\n", "test_rect", 2, "3-bounds")
    case("bounds_velocity_huge.toml", BASE + "\n[preparation]\nvelocity_amplitude = 1e300\n", "velocity_amplitude", 2, "3-bounds")
    case("bounds_particle_velocity_huge.toml", sub(BASE, "count = 10", "count = 1") +
         "\n[[preparation.particle]]\nx = 0.01\ny = 0.01\nvx = 1e308\n", "vx", 2, "3-bounds")
    case("bounds_gravity_huge.toml", P + '\n[drive]\nkind = "gravity"\ng = 1e307\n', "drive.g", 2, "3-bounds")
    case("bounds_g_p_huge.toml", P + '\n[drive]\nkind = "negative_g"\ng_p = 1e300\ntaps = 1\n', "g_p", 2, "3-bounds")
    case("bounds_ks_huge.toml", sub(BASE, "ks = 5e5", "ks = 1e300"), "ks", 2, "3-bounds")
    case("bounds_mass_tiny.toml", sub(BASE, "mass = 3.53e-5", "mass = 1e-300"), "mass", 2, "3-bounds")
    case("bounds_density_tiny.toml", sub(P, "count = 10", "count = 10\ndensity = 1e-300"), "density", 2, "3-bounds")
    case("bounds_frames_slowmo.toml", BASE + "\n[render]\nenabled = true\nfps = 240\nslowmo = 1e300\n", "render.slowmo", 2, "3-bounds")
    case("bounds_frames_every_step.toml", sub(BASE, "duration = 0.001", "duration = 1000.0") +
         '\n[render]\nenabled = true\nschedule = "steps"\nevery = 1\n', "render.every", 2, "3-bounds")
    case("bounds_trajectory_huge.toml", sub(BASE, "duration = 0.001", "duration = 10000.0") +
         "\n[render]\ntrajectory_every = 1\n", "trajectory_every", 2, "3-bounds")
    case("bounds_t1_below_dt.toml", P + '\n[drive]\nkind = "negative_g"\nt1 = 1e-6\nperiod = 0.5\ntaps = 2\n', "drive.t1", 2, "3-bounds")
    case("bounds_rotation_too_fast.toml", P + '\n[drive]\nkind = "rotating_g"\nf = 1e9\ntaps = 2\n', "drive.f", 2, "3-bounds")
    case("bounds_taps_overflow.toml", P + '\n[drive]\nkind = "negative_g"\nperiod = 100.0\ntaps = 2000000000\n', "integrator.dt", 2, "3-bounds")
    case("bounds_settle_huge.toml", BASE + "\n[preparation]\nsettle_time = 1e30\n", "integrator.dt", 2, "3-bounds")
    case("bounds_dt_tiny.toml", sub(BASE, "dt = 1e-6", "dt = 1e-300"), "integrator.dt", 2, "3-bounds")
    case("bounds_duration_huge.toml", sub(BASE, "duration = 0.001", "duration = 1e300"), "integrator.dt", 2, "3-bounds")

    # ---- class 4: inputs that would hang or exhaust memory
    case("hang_period_tiny.toml", P + '\n[drive]\nkind = "negative_g"\nperiod = 1e-300\nt1 = 1e-301\ntaps = 3\n', "drive.t1", 2, "4-hang")
    case("hang_box_smaller_than_grain.toml", sub(BASE, "width = 0.05", "width = 0.001"), "fit", 2, "4-hang")
    case("hang_walls_narrower_than_grain.toml", sub(P, "width = 0.2", "width = 0.01"), "fit", 2, "4-hang")
    case("mem_particles_1e8.toml", sub(sub(BASE, "count = 10", "count = 100000000"), "width = 0.05", "width = 100.0"),
         "memory", 2, "4-hang")
    command("4-hang", 2, "species", "run {gen_species} --out {out} --quiet")
    command("4-hang", 2, "FIFO", "run {fifo} --out {out} --quiet")
    command("4-hang", 2, "character device", "run /dev/zero --out {out} --quiet")
    command("4-hang", 2, "FIFO", "analyze --series negative_g:6:{fifo_csv} --test-area 0.01 --out {out} -q")
    command("4-hang", 2, "FIFO", "analyze --manifest {fifo_csv} --test-area 0.01 --out {out} -q")
    command("4-hang", 2, "FIFO", "render {fifo_csv} --scene {run}/scene.toml -o {out}.png")
    command("4-hang", 2, "FIFO", "render {fifo_gsck} -o {out}.png")
    command("4-hang", 2, "character device", "render /dev/zero --scene {run}/scene.toml -o {out}.png")
    command("4-hang", 2, "FIFO", "model walk --paths {fifo_csv} --out {out} --no-charts -q")
    command("4-hang", 2, "FIFO", "sweep {fifo} --param drive.kind=none --out {out} -q")
    command("4-hang", 2, "--replicas", "sweep {run}/scene.toml --param drive.kind=none --replicas 1000000000 --out {out} -q")
    command("4-hang", 2, "realisations", "model bisection --realisations 1000000000000000 --out {out} --no-charts -q")
    command("4-hang", 2, "realisations", "model cascade --realisations 1000000000 --out {out} --no-charts -q")
    command("4-hang", 2, "walks", "model interval --walks 100000000000 --out {out} --no-charts -q")
    command("4-hang", 2, "the same", "analyze --series negative_g:6:{gen_constant} --test-area 0.01 --out {out} --no-charts -q")
    # schedules finer than a step: refused up front, never counted through
    case("hang_snapshots_every_time_tiny.toml", BASE + "\n[output.snapshots]\nevery_time = 1e-300\n", "every_time", 2, "4-hang")
    case("hang_snapshots_every_time_below_dt.toml", BASE + "\n[output.snapshots]\nevery_time = 5e-7\n", "integrator.dt", 2, "4-hang")
    command("4-hang", 2, "--dt", "model walk --dt 1e-300 --walks 10 --radius 0.001 --out {out} --no-charts -q --no-heating")
    command("4-hang", 2, "--dt", "model interval --dt 1e-300 --walks 10 --out {out} --no-charts -q")
    # a length no walk can cross: refused, never a null result with exit 0
    command("5-data", 2, "--length",
            "model interval --length 1e308 --walks 10 --out {out} --no-charts -q")

    # ---- class 5: bad data (exit 2 naming file, line, column) and unwritable outputs (exit 5)
    case("series_phi_nan.csv", "tap,phi\n1,0.8\n2,nan\n3,0.81\n", ":3", 2, "5-data", SERIES)
    case("series_phi_inf.csv", "tap,phi\n1,0.8\n2,0.81\n3,-inf\n", ":4", 2, "5-data", SERIES)
    case("series_t_nan.csv", "tap,t,phi\n1,0.5,0.8\n2,nan,0.81\n", "column 2", 2, "5-data", SERIES)
    case("series_no_phi_column.csv", "tap,t\n1,0.5\n2,1.0\n", "missing column 'phi'", 2, "5-data", SERIES)
    case("series_text_value.csv", "tap,phi\n1,0.8\n2,abc\n", "not a number", 2, "5-data", SERIES)
    case("series_short_row.csv", "tap,t,phi\n1,0.5,0.8\n2,1.0\n", "no value", 2, "5-data", SERIES)
    case("series_empty.csv", "", "no header", 2, "5-data", SERIES)
    case("series_too_short.csv", "tap,phi\n1,0.8\n2,0.81\n", "need at least", 2, "5-data", SERIES)
    case("paths_missing_P.csv", "l,Q\n0.001,1\n0.002,2\n", "missing column 'P'", 2, "5-data", WALK)
    case("paths_repeated_column.csv", "l,P,P\n0.001,1,1\n0.002,2,2\n", "repeated column", 2, "5-data", WALK)
    case("paths_short_row.csv", "l,P\n0.001,1\n0.002\n", "expected 2 values", 2, "5-data", WALK)
    case("paths_not_increasing.csv", "l,P\n0.002,1\n0.001,2\n", "increasing", 2, "5-data", WALK)
    case("paths_text.csv", "l,P\n0.001,one\n", "not a number", 2, "5-data", WALK)
    case("state_nan.csv", STATE_HEAD + state_rows(9) + "9,bead,nan,0.01,0,0,0,0\n", "not finite", 2, "5-data", RENDER)
    case("state_inf_velocity.csv", STATE_HEAD + state_rows(9) + "9,bead,0.04,0.01,0,inf,0,0\n", "not finite", 2, "5-data", RENDER)
    case("state_unknown_species.csv", STATE_HEAD + state_rows(10, "ghost"), "unknown species", 2, "5-data", RENDER)
    command("5-data", 5, "cannot write output", "model bisection --realisations 10 --out /proc/gransim-forbidden --no-charts -q")
    command("5-data", 5, "", "render {run} -o /proc/gransim-forbidden.png")

    # ---- class 6: truncated, garbled and inconsistent files
    case("state_cut_mid_row.csv", (GOOD_STATE)[:-7], "truncated", 2, "6-truncated", RENDER)
    case("state_missing_rows.csv", STATE_HEAD + state_rows(5), "n=10", 2, "6-truncated", RENDER)
    case("state_garbage_number.csv", STATE_HEAD + state_rows(9) + "9,bead,0.12GARBAGE,0.01,0,0,0,0\n", "0.12GARBAGE", 2, "6-truncated", RENDER)
    case("state_empty.csv", "", "empty", 2, "6-truncated", RENDER)
    case("state_header_only.csv", STATE_HEAD, "no particle rows", 2, "6-truncated", RENDER)
    case("state_extra_column.csv", STATE_HEAD + state_rows(9) + "9,bead,0.04,0.01,0,0,0,0,7\n", "8 columns", 2, "6-truncated", RENDER)
    case("state_bad_header.csv", "# gransim state v1\n# t=abc step=1\n" + state_rows(), "header", 2, "6-truncated", RENDER)
    case("taps_duplicated.csv", "tap,phi\n" + "".join(f"{i},0.8{i % 7}\n" for i in [1, 2, 3, 3, 4] + list(range(5, 40))), "increase", 2, "6-truncated", SERIES)
    case("taps_reversed.csv", "tap,phi\n" + "".join(f"{i},0.8{i % 7}\n" for i in range(40, 0, -1)), "increase", 2, "6-truncated", SERIES)
    command("6-truncated", 2, "missing", "movie {run_gap} -o {out}.mp4 -q")
    command("6-truncated", 0, "", "movie {run} -o {out}.mp4 -q")
