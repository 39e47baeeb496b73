use isochor_solvers::linear::*;
use isochor_solvers::{Method, Settings, Simulation};
#[path = "../tests/common.rs"]
mod common;
fn main() {
    let res: usize = std::env::args().nth(1).unwrap().parse().unwrap();
    let nu: f64 = std::env::args().nth(2).unwrap().parse().unwrap();
    let problem = common::cantilever(res, Method::Standard, nu);
    let mut sim = Simulation::new(problem, Settings::default()).unwrap();
    let state = sim.state().clone();
    let m = sim.matrices(&state).unwrap();
    let n = m.free.len();
    let (pairs, values): (Vec<_>, Vec<_>) = m.stiffness.iter().filter(|(_, (r, c))| r >= c).map(|(v, (r, c))| ((r, c), *v)).unzip();
    let k = SparsityPattern::new(n, n, &pairs, Triangle::Lower).unwrap().assemble(&values).unwrap();
    let t = std::time::Instant::now();
    let amg = SmoothedAggregation::new(k.as_ref(), NearNullSpace::rigid_body(&m.free, &state.positions)).unwrap();
    let setup = t.elapsed();
    let b: Vec<f64> = (0..n).map(|i| ((i * 7919) % 101) as f64 / 101.0 - 0.5).collect();
    let mut x = vec![0.0; n];
    let t = std::time::Instant::now();
    let r = cg(&SymmetricLower(k.as_ref()), &amg, &b, &mut x, IterativeOptions { tolerance: 1e-8, max_iterations: 5000 }).unwrap();
    let solve = t.elapsed();
    let t = std::time::Instant::now();
    let ic = IncompleteCholesky::new(k.as_ref()).unwrap();
    let ics = t.elapsed();
    let mut x = vec![0.0; n];
    let t = std::time::Instant::now();
    let r2 = cg(&SymmetricLower(k.as_ref()), &ic, &b, &mut x, IterativeOptions { tolerance: 1e-8, max_iterations: 50000 }).unwrap();
    let ic_solve = t.elapsed();
    let t = std::time::Instant::now();
    let mut ch = CholeskySolver::new(k.symbolic()).unwrap();
    ch.factorize(k.as_ref(), 0.0).unwrap();
    let chol = t.elapsed();
    println!("n {n} levels {:?}: AMG setup {:?}, {} its {:?}; IC setup {:?}, {} its {:?}; Cholesky {:?}", amg.level_sizes(), setup, r.iterations, solve, ics, r2.iterations, ic_solve, chol);
}
