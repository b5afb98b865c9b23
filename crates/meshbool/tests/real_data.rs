//! Measures and format round-trips on the real Kirra surfaces shipped in `data/`.

use meshbool::io::{self, Format};
use meshbool::measure::{mesh_stats, MeshStats};
use meshbool::Mesh;

fn data(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(name)
}

fn stats(name: &str) -> MeshStats {
    mesh_stats(&io::read_path(data(name)).unwrap())
}

#[test]
fn kirra_terrain_counts() {
    for name in ["kirra_terrain.obj", "kap_terrain.obj"] {
        let s = stats(name);
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
        let s = stats(name);
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
        let s = stats(name);
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

/// Volume is computed about the bounding-box centre: moving the cylinder to UTM
/// coordinates changes it only by the rounding of the moved coordinates.
#[test]
fn volume_keeps_precision_at_utm_offsets() {
    let m = io::read_path(data("kirra_cylinder.obj")).unwrap();
    let mut far = m.clone();
    for p in far.positions_mut() {
        *p = [p[0] + 478_600.0, p[1] + 6_772_300.0, p[2] + 350.0];
    }
    let (a, b) = (mesh_stats(&m).volume, mesh_stats(&far).volume);
    assert!((a - b).abs() <= 1e-9 * a.abs(), "{a} vs {b}");
    // The shipped UTM cylinder is a separately rounded copy: equal to 4-decimal precision.
    let kap = stats("kap_cylinder.obj").volume;
    assert!((a - kap).abs() <= 1e-6 * a.abs(), "{a} vs {kap}");
}

#[test]
fn json_and_obj_cup_are_the_same_soup() {
    let obj = io::read_path(data("kirra_cup.obj")).unwrap();
    let json = io::read_path(data("kirra_cup.json")).unwrap();
    assert_eq!(obj.to_soup(), json.to_soup());
}

/// Every exact format carries the UTM terrain through unchanged: same corners bit for bit,
/// same topology, same volume and area.
#[test]
fn utm_terrain_round_trips_every_exact_format() {
    let m = io::read_path(data("kap_terrain.obj")).unwrap();
    let want = mesh_stats(&m);
    let dir = std::env::temp_dir().join(format!("meshbool-rt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
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
    std::fs::remove_dir_all(&dir).unwrap();
}

/// glTF stores `f32` offsets from the bounding box's centre (kept in `f64`): the UTM
/// terrain comes back with the same triangles, every coordinate within `2^-24` of half the
/// box's size (plus an `f64` rounding), and the same area to about that.
#[test]
fn utm_terrain_round_trips_glb() {
    let m = io::read_path(data("kap_terrain.obj")).unwrap();
    let mut bytes = Vec::new();
    io::write(&mut bytes, &m, Format::Glb).unwrap();
    let back = io::read_bytes(&bytes, Format::Glb).unwrap();
    assert_eq!(back.triangles(), m.triangles());
    let half = m.bounds().unwrap().size().map(|s| s / 2.0);
    for (p, q) in m.positions().iter().zip(back.positions()) {
        for k in 0..3 {
            let bound = half[k] * 2f64.powi(-24) + p[k].abs() * 2f64.powi(-52);
            assert!((p[k] - q[k]).abs() <= bound, "{p:?} came back as {q:?}");
        }
    }
    let (a, b) = (mesh_stats(&m), mesh_stats(&back));
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
    let m = io::read_path(data("kirra_terrain.obj")).unwrap();
    let mut bytes = Vec::new();
    io::write(&mut bytes, &m, Format::StlBinary).unwrap();
    let back = io::read_bytes(&bytes, Format::StlBinary).unwrap();
    let (a, b) = (mesh_stats(&back), mesh_stats(&m));
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
