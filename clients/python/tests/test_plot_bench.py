"""`python -m contact_client.plot_bench` turns a `contact-bench` CSV into a PNG."""

from __future__ import annotations

import subprocess
import sys

import pytest

pytest.importorskip("matplotlib")

HEADER = (
    "scene,element,h_min,dofs,candidates,method,iterations,t_mesh,t_assembly,t_factorization,"
    "t_condensation,t_contact,t_post,t_total,t_floor,ratio_solve_to_floor,ratio_total_to_floor,"
    "err_half_width,err_peak,err_l2,max_penetration,certificate,status"
)
# Two meshes x two methods, one row not solved (hollow marker), a ζ in a method name.
ROWS = [
    "hertz_block,T3,0.04,15500,99,active_set,6,0.0002,0.01,0.029,0.0002,0.0001,0.0002,0.0438,0.0269,1.086,1.627,-9.5e-3,4.0e-3,1.9e-2,3.5e-17,2.9e-13,solved",
    "hertz_block,T3,0.04,15500,99,penalty(ζ=1e-6),6,0.0001,0.005,0.016,0.0001,0.0001,0.0002,0.0227,0.0269,0.604,0.842,-9.5e-3,3.9e-3,1.87e-2,9.5e-6,7.9e-5,solved",
    "hertz_block,T3,0.02,31862,153,active_set,7,0.0002,0.012,0.052,0.0002,0.0008,0.0004,0.0724,0.0380,1.395,1.905,-9.4e-3,2.2e-3,1.1e-2,3.5e-17,2.2e-12,solved",
    "hertz_block,T3,0.02,31862,153,penalty(ζ=1e-6),7,0.0001,0.013,0.043,0.0003,0.0007,0.0004,0.0629,0.0380,1.159,1.654,-9.4e-3,2.0e-3,1.07e-2,9.4e-6,7.9e-5,maxiterations",
]
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def _csv(tmp_path):
    path = tmp_path / "bench.csv"
    path.write_text("\n".join([HEADER, *ROWS]) + "\n", encoding="utf-8")
    return path


def test_writes_png_next_to_csv(tmp_path):
    csv_path = _csv(tmp_path)
    cp = subprocess.run([sys.executable, "-m", "contact_client.plot_bench", str(csv_path)],
                        capture_output=True, text=True, timeout=120)
    assert cp.returncode == 0, cp.stderr
    png = tmp_path / "bench.png"
    assert png.is_file() and png.stat().st_size > 0
    assert png.read_bytes()[:8] == PNG_MAGIC


def test_out_and_title(tmp_path):
    from contact_client.plot_bench import main

    out = tmp_path / "sub" / "fig.png"
    assert main([str(_csv(tmp_path)), "--out", str(out), "--title", "test machine, 2 threads"]) == 0
    assert out.is_file() and out.stat().st_size > 0
    assert out.read_bytes()[:8] == PNG_MAGIC
