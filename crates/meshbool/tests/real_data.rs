//! Measures of the real Kirra surfaces (other projects' data, read from `../shared/data`
//! beside the checkout; skipped where it is absent), and format round trips of terrains:
//! a generated one always, the real one where it is there.

#[allow(dead_code)]
mod common;

use meshbool::io::{self, Format};
use meshbool::measure::{mesh_stats, MeshStats};
use meshbool::{shapes, Mesh};

/// A real surface, or `None` (the test skipped) without `../shared/data`.
fn real(name: &str) -> Option<Mesh> {
    common::shared_data(name).map(|p| io::read_path(p).unwrap())
}

fn stats(name: &str) -> Option<MeshStats> {
    real(name).map(|m| mesh_stats(&m))
}

/// A generated terrain about `center` (7200 triangles, five of them reversed: badly
/// wound, as surveys are), and the real terrain `name` where `../shared/data` has it.
fn terrains(center: [f64; 3], name: &str) -> Vec<Mesh> {
    let mut t = shapes::terrain(center, [600.0; 2], [60; 2], 40.0, 1).unwrap();
    let mut triangles = t.triangles().to_vec();
    for k in [610, 1100, 6010, 6500, 3620] {
        triangles[k].swap(1, 2);
    }
    t = Mesh::new(t.positions().to_vec(), triangles).unwrap();
    assert_eq!(mesh_stats(&t).inconsistent_edges, 15);
    let mut all = vec![t];
    all.extend(real(name));
    all
}

/// A centre at UTM-like coordinates (metres east and north, elevation).
const UTM: [f64; 3] = [478_600.0, 6_772_300.0, 400.0];

#[test]
fn kirra_terrain_counts() {
    for name in ["kirra_terrain.obj", "kap_terrain.obj"] {
        let Some(s) = stats(name) else { return };
        assert_eq!(s.triangles, 11200, "{name}");
        assert_eq!(s.vertices, 5881, "{name}");
        assert_eq!(s.boundary_edges, 560, "{name}");
        assert_eq!(s.non_manifold_edges, 0, "{name}");
        assert_eq!(s.inconsistent_edges, 46, "{name}");
        assert_eq!(s.components, 1, "{name}");
        assert!(!s.closed);
    }
}

#[test]
fn kirra_cylinder_is_closed_and_cup_is_open() {
    for name in ["kirra_cylinder.obj", "kap_cylinder.obj"] {
        let Some(s) = stats(name) else { return };
        assert_eq!(
            (
                s.triangles,
                s.vertices,
                s.boundary_edges,
                s.inconsistent_edges
            ),
            (60, 32, 0, 0)
        );
        assert!(s.closed, "{name}");
        assert!(s.volume.abs() > 0.0);
    }
    for name in [
        "kirra_cup.obj",
        "kap_cup.obj",
        "kirra_cup.stl",
        "kirra_cup.json",
    ] {
        let Some(s) = stats(name) else { return };
        assert_eq!(
            (
                s.triangles,
                s.vertices,
                s.boundary_edges,
                s.non_manifold_edges
            ),
            (16, 12, 6, 0),
            "{name}"
        );
    }
}

/// Volume is computed about the bounding-box centre: moving a cylinder to UTM
/// coordinates changes it only by the rounding of the moved coordinates.
#[test]
fn volume_keeps_precision_at_utm_offsets() {
    let drill = shapes::cylinder([20.0, -10.0, -60.0], 35.0, 120.0, 30).unwrap();
    let kirra = real("kirra_cylinder.obj");
    for m in std::iter::once(&drill).chain(&kirra) {
        let mut far = m.clone();
        for p in far.positions_mut() {
            *p = [p[0] + 478_600.0, p[1] + 6_772_300.0, p[2] + 350.0];
        }
        let (a, b) = (mesh_stats(m).volume, mesh_stats(&far).volume);
        assert!((a - b).abs() <= 1e-9 * a.abs(), "{a} vs {b}");
    }
    // The real UTM cylinder is a separately rounded copy: equal to 4-decimal precision.
    let (Some(m), Some(kap)) = (kirra, stats("kap_cylinder.obj")) else {
        return;
    };
    let (a, kap) = (mesh_stats(&m).volume, kap.volume);
    assert!((a - kap).abs() <= 1e-6 * a.abs(), "{a} vs {kap}");
}

#[test]
fn json_and_obj_cup_are_the_same_soup() {
    let (Some(obj), Some(json)) = (real("kirra_cup.obj"), real("kirra_cup.json")) else {
        return;
    };
    assert_eq!(obj.to_soup(), json.to_soup());
}

/// Every exact format carries the UTM terrain through unchanged: same corners bit for bit,
/// same topology, same volume and area.
#[test]
fn utm_terrain_round_trips_every_exact_format() {
    let dir = std::env::temp_dir().join(format!("meshbool-rt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for m in terrains(UTM, "kap_terrain.obj") {
        let want = mesh_stats(&m);
        for (name, f) in Format::NAMES {
            // f32 formats: binary STL below, glTF in `utm_terrain_round_trips_glb`.
            if matches!(f, Format::StlBinary | Format::Glb) {
                continue;
            }
            let path = dir.join(format!("t.{name}"));
            io::write_path_as(&path, &m, f).unwrap();
            let back = io::read_path(&path).unwrap();
            assert_eq!(back.to_soup(), m.to_soup(), "{name}");
            assert_eq!(mesh_stats(&back), want, "{name}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// glTF stores `f32` offsets from the bounding box's centre (kept in `f64`): the UTM
/// terrain comes back with the same triangles, every coordinate within `2^-24` of half the
/// box's size (plus an `f64` rounding), and the same area to about that.
#[test]
fn utm_terrain_round_trips_glb() {
    for m in terrains(UTM, "kap_terrain.obj") {
        round_trips_glb(&m);
    }
}

fn round_trips_glb(m: &Mesh) {
    let mut bytes = Vec::new();
    io::write(&mut bytes, m, Format::Glb).unwrap();
    let back = io::read_bytes(&bytes, Format::Glb).unwrap();
    assert_eq!(back.triangles(), m.triangles());
    let half = m.bounds().unwrap().size().map(|s| s / 2.0);
    for (p, q) in m.positions().iter().zip(back.positions()) {
        for k in 0..3 {
            let bound = half[k] * 2f64.powi(-24) + p[k].abs() * 2f64.powi(-52);
            assert!((p[k] - q[k]).abs() <= bound, "{p:?} came back as {q:?}");
        }
    }
    let (a, b) = (mesh_stats(m), mesh_stats(&back));
    assert_eq!(
        (a.vertices, a.edges, a.boundary_edges, a.inconsistent_edges),
        (b.vertices, b.edges, b.boundary_edges, b.inconsistent_edges)
    );
    assert!(
        (a.area - b.area).abs() <= a.area * 1e-6,
        "{} {}",
        a.area,
        b.area
    );
}

#[test]
fn binary_stl_keeps_topology_of_centred_terrain() {
    for m in terrains([0.0; 3], "kirra_terrain.obj") {
        binary_stl_keeps_topology(&m);
    }
}

fn binary_stl_keeps_topology(m: &Mesh) {
    let mut bytes = Vec::new();
    io::write(&mut bytes, m, Format::StlBinary).unwrap();
    let back = io::read_bytes(&bytes, Format::StlBinary).unwrap();
    let (a, b) = (mesh_stats(&back), mesh_stats(m));
    assert_eq!(
        (
            a.triangles,
            a.vertices,
            a.boundary_edges,
            a.inconsistent_edges
        ),
        (
            b.triangles,
            b.vertices,
            b.boundary_edges,
            b.inconsistent_edges
        )
    );
    assert!((a.area - b.area).abs() < 1e-4 * b.area);
    assert_eq!(Mesh::from_soup(&back.to_soup()), back);
}
