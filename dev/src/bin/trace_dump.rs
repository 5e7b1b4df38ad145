//! Prints, for one paper example and method, each root's tri-box diameter by
//! level — the raw material of Tables 1–6.
//!
//! `cargo run --release -p rootclip-dev --bin trace_dump -- 2 hc`
use rootclip::internals::repro;
use rootclip::solve::Method;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let name = args.get(1).map_or("1", String::as_str);
    let method: Method = args.get(2).map_or("hc", String::as_str).parse()?;
    let ex = repro::examples()?
        .into_iter()
        .find(|e| e.name == name)
        .ok_or("unknown example")?;
    let sol = repro::run(&ex, method, 1e-14, repro::Variant::DEFAULT)?;
    for r in &sol.roots {
        let d: Vec<String> = r.diameters.iter().map(|x| format!("{x:.2e}")).collect();
        println!("root ({:.6}, {:.6}): {}", r.u, r.v, d.join(" "));
    }
    for c in &sol.clusters {
        println!("cluster {:?}", c.bx);
    }
    println!("{:?}", sol.stats);
    Ok(())
}
