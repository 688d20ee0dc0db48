"""Writes countries of Natural Earth 1:10m as GeoJSON, with every island and hole, from the
TopoJSON of the npm package `world-atlas` 2.0.2 (`countries-10m.json`).

    npm pack world-atlas@2.0.2 && tar xzf world-atlas-2.0.2.tgz
    python3 extract.py package/countries-10m.json OUT_DIR

TopoJSON stores shared borders once as arcs, quantized and delta-encoded; a ring lists
arcs by index (a negative index ~i means arc i reversed). Decoding: undo the deltas,
apply the transform (scale and translate), then join each ring's arcs, dropping the first
point of every arc after the first (it repeats the previous arc's last point). Rings are
written as GeoJSON writes them, the first point repeated at the end; coordinates are
longitude and latitude in degrees, rounded to 1e-7 (the quantized grid is coarser).
"""

import json
import sys
from pathlib import Path

COUNTRIES = {
    "Italy": "italy",  # two holes: San Marino and the Vatican
    "San Marino": "san-marino",  # the hole in Italy, as a country of its own
    "South Africa": "south-africa",  # a hole: Lesotho; islands far away
    "Lesotho": "lesotho",
    "Indonesia": "indonesia",  # hundreds of islands
}


def decode_arcs(topology):
    scale = topology["transform"]["scale"]
    translate = topology["transform"]["translate"]
    arcs = []
    for arc in topology["arcs"]:
        x = y = 0
        points = []
        for dx, dy in arc:
            x += dx
            y += dy
            points.append([
                round(x * scale[0] + translate[0], 7),
                round(y * scale[1] + translate[1], 7),
            ])
        arcs.append(points)
    return arcs


def ring(arcs, indices):
    points = []
    for k, index in enumerate(indices):
        arc = arcs[index] if index >= 0 else list(reversed(arcs[~index]))
        points.extend(arc if k == 0 else arc[1:])
    return points


def main():
    source, out = Path(sys.argv[1]), Path(sys.argv[2])
    topology = json.loads(source.read_text())
    arcs = decode_arcs(topology)
    for geometry in topology["objects"]["countries"]["geometries"]:
        name = geometry["properties"]["name"]
        if name not in COUNTRIES:
            continue
        polygons = geometry["arcs"] if geometry["type"] == "MultiPolygon" else [geometry["arcs"]]
        coordinates = [[ring(arcs, r) for r in polygon] for polygon in polygons]
        feature = {
            "type": "Feature",
            "properties": {"name": name, "source": "Natural Earth 1:10m via world-atlas 2.0.2"},
            "geometry": {"type": "MultiPolygon", "coordinates": coordinates},
        }
        path = out / f"{COUNTRIES[name]}.geojson"
        path.write_text(json.dumps(feature, separators=(",", ":")) + "\n")
        rings = sum(len(p) for p in coordinates)
        vertices = sum(len(r) for p in coordinates for r in p)
        print(f"{path.name}: {len(coordinates)} polygons, {rings} rings, {vertices} points")


if __name__ == "__main__":
    main()
