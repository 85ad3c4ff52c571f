//! The import's phases on one drawing, median wall time of several runs: reading the DXF into
//! elements (curves fitted; its first steps, group codes and sections, also timed alone), chaining them into contours, nesting contours into pockets, and
//! the read rate. `cargo run --release --bin import -- FILE.dxf [RUNS]`.

use pocketeer::ImportOptions;
use std::time::Instant;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let Some(path) = args.get(1) else {
        eprintln!("usage: import FILE.dxf [RUNS]");
        std::process::exit(2);
    };
    let runs: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(5);
    let bytes = std::fs::read(path).expect("the drawing reads");
    let options = ImportOptions::default();
    let (mut read, mut chain, mut nest) = (Vec::new(), Vec::new(), Vec::new());
    let (mut groups, mut document) = (Vec::new(), Vec::new());
    let mut elements = 0;
    for _ in 0..runs {
        // The reader's first two steps alone: group codes, then sections and entities.
        let t = Instant::now();
        let list = pocketeer::import::dxf::GroupList::read(&bytes).expect("the groups read");
        groups.push(t.elapsed().as_secs_f64());
        let t = Instant::now();
        let doc = pocketeer::import::dxf::parse_document(&list).expect("the sections read");
        document.push(t.elapsed().as_secs_f64());
        std::hint::black_box(doc);
        let t = Instant::now();
        let drawing = pocketeer::read_drawing(&bytes, &options).expect("the drawing imports");
        read.push(t.elapsed().as_secs_f64());
        elements = drawing.elements.len();
        let tol = drawing.tolerance(options.join_tolerance);
        let t = Instant::now();
        let chains = pocketeer::import::chain(&drawing.elements, &tol, options.close_gaps);
        chain.push(t.elapsed().as_secs_f64());
        let t = Instant::now();
        let nesting =
            pocketeer::import::find_pockets(&chains.contours, &drawing.layers, &tol, Some(options.fill))
                .expect("the contours nest");
        nest.push(t.elapsed().as_secs_f64());
        std::hint::black_box(nesting);
    }
    let (r, c, n) = (median(read), median(chain), median(nest));
    println!(
        "{path}: {:.1} MB, {elements} elements; read {:.0} ms ({:.1} MB/s; groups {:.0} ms, sections {:.0} ms), chain {:.0} ms, nest {:.0} ms, total {:.0} ms (medians of {runs})",
        bytes.len() as f64 / 1e6,
        1e3 * r,
        bytes.len() as f64 / 1e6 / r,
        1e3 * median(groups),
        1e3 * median(document),
        1e3 * c,
        1e3 * n,
        1e3 * (r + c + n)
    );
}
