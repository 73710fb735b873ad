"""plot_rtf_error.py draws a PNG from rtf_error_benchmark's CSV (with closed_loop_benchmark's and
reduced_benchmark's beside it, or not) and rejects a CSV it cannot use.

Usage: test_plot_rtf_error.py SCRIPT
"""
import os
import subprocess
import sys
import tempfile

HEADER = ("dt_ms,tolerance,newton,material,threads,steps,iterations,factorizations,wall_s,rtf,"
          "rtf_cpu,rms_mm,worst_frame_rms_mm,max_mm\n")
ROWS = [
    "4,default,reuse,mooney_rivlin5,1,80,295,3,0.36,0.9,0.9,0.0426,0.133,0.58\n",
    "4,loose,reuse,mooney_rivlin5,2,80,262,3,0.36,0.9,0.9,0.0426,0.133,0.58\n",
    "10,default,full,mooney_rivlin5,1,32,68,68,3.0,0.1,0.1,0.109,0.31,1.34\n",
    "4,default,reuse,neo_hookean,1,80,290,4,0.53,0.6,0.8,0.141,0.27,1.14\n",
    "2,default,reuse,exponential,1,160,450,5,1.0,0.3,0.5,0.0767,0.13,0.36\n",
]
CLOSED_LOOP = ("scenario,threads,rtf,physics_ms,server_ms,rms_mm\n"
               "ai,1,2.4,1.3,1.5,0.317\n"
               "ai,2,2.3,1.4,1.6,0.317\n"
               "ku,1,2.6,1.2,1.3,nan\n")
REDUCED = ("basis,modes,sampled,rtf,full_rtf,rms_mm,max_mm,runs,stable_runs,stable_worst_rms_mm\n"
           "a.h5,49,485,4.7,3.1,1.22,13.7,34,17,0.70\n"
           "b.h5,78,555,2.9,2.8,1.15,13.6,34,17,0.49\n")


def run(script, *args):
    return subprocess.run([sys.executable, script, *args], capture_output=True, text=True)


def main():
    script = sys.argv[1]
    with tempfile.TemporaryDirectory() as d:
        csv_path, png_path = os.path.join(d, "r.csv"), os.path.join(d, "r.png")
        with open(csv_path, "w") as f:
            f.write(HEADER + "".join(ROWS))
        result = run(script, csv_path, png_path)
        assert result.returncode == 0, result.stderr
        with open(png_path, "rb") as f:
            assert f.read(8) == b"\x89PNG\r\n\x1a\n", "not a PNG"
        assert os.path.getsize(png_path) > 10000, "suspiciously small picture"

        closed = os.path.join(d, "closed.csv")
        with open(closed, "w") as f:
            f.write(CLOSED_LOOP)
        both = os.path.join(d, "both.png")
        result = run(script, csv_path, both, "--closed-loop", closed)
        assert result.returncode == 0, result.stderr
        with open(both, "rb") as f:
            assert f.read(8) == b"\x89PNG\r\n\x1a\n", "not a PNG"
        # The star and its label change the picture.
        with open(png_path, "rb") as a, open(both, "rb") as b:
            assert a.read() != b.read(), "the closed-loop rows were not drawn"

        reduced = os.path.join(d, "reduced.csv")
        with open(reduced, "w") as f:
            f.write(REDUCED)
        three = os.path.join(d, "three.png")
        result = run(script, csv_path, three, "--closed-loop", closed, "--reduced", reduced)
        assert result.returncode == 0, result.stderr
        with open(both, "rb") as a, open(three, "rb") as b:
            assert a.read() != b.read(), "the reduced model's rows were not drawn"

        bad = os.path.join(d, "bad.csv")
        with open(bad, "w") as f:
            f.write("dt_ms,rtf\n4,0.9\n")
        result = run(script, bad, os.path.join(d, "bad.png"))
        assert result.returncode != 0
        assert "bad.csv" in result.stderr and "missing columns" in result.stderr, result.stderr
        result = run(script, csv_path, os.path.join(d, "bad2.png"), "--closed-loop", bad)
        assert result.returncode != 0
        assert "bad.csv" in result.stderr and "missing columns" in result.stderr, result.stderr
        result = run(script, csv_path, os.path.join(d, "bad3.png"), "--reduced", bad)
        assert result.returncode != 0
        assert "bad.csv" in result.stderr and "missing columns" in result.stderr, result.stderr


if __name__ == "__main__":
    main()
