# Matches two mesh files, writes both maps (1-based, one index per line) and prints what the run
# did: python3 match_files.py SOURCE TARGET OUT_12 OUT_21
import sys

import comap

V1, F1 = comap.read_mesh(sys.argv[1])
V2, F2 = comap.read_mesh(sys.argv[2])


def progress(stage, fraction):
    if fraction == 1.0:
        print(f"{stage} done", file=sys.stderr)


map_12, map_21, info = comap.match(V1, F1, V2, F2, progress=progress)
comap.write_map(sys.argv[3], map_12)
comap.write_map(sys.argv[4], map_21)
print("\n".join(info["decisions"]))
print(f"inconsistent vertices: {comap.inconsistent_vertices(map_12, map_21)}")
print(f"mean cycle error: {comap.cycle_errors(V1, F1, map_12, map_21).mean():.4f}")
print(f"coverage: {comap.coverage(map_12, len(V2)):.3f}, time: {info['stage_seconds']['total']:.1f} s")
