//! Zonal volume constraints: one constraint per zone of elements, zones possibly overlapping
//! (eq. 6-9 of Sheen et al. 2021).

use crate::measured::{check_len, inverse_bulk_modulus, MeasuredElements};
use crate::{Compliance, ConstraintError, ConstraintSet, Measure, RowShape};
use isochor_mesh::element::TetQuadrature;
use isochor_mesh::{ElementMesh, ElementSurface, TetMesh, Vec3, Zones};
use rayon::prelude::*;

/// One constraint per zone `j`: `c_j = sum_{e in zone j} integral_e (J - 1) dV` (eq. 6; the
/// zone's volume change), hard by default (`C = 0`, eq. 7-8), optionally compliant
/// ([`ZonalConstraints::with_bulk_modulus`]).
///
/// Zones may overlap; an element in several zones contributes to each of their rows. The
/// Jacobian pattern holds, for every zone in order and every element of the zone in order,
/// `3n` entries (the zone's row over the element's DOFs): zone rows are dense over the zone.
/// The geometric stiffness holds one `3n x 3n` block per element that belongs to any zone,
/// weighted by the sum of the multipliers of the zones that contain it (eq. 9 differentiated
/// twice).
#[derive(Debug, Clone)]
pub struct ZonalConstraints {
    elements: MeasuredElements,
    zones: Vec<Vec<usize>>,
    rest_zone_volumes: Vec<f64>,
    compliance: Vec<f64>,
    /// `(zone, element)` of every Jacobian block.
    entries: Vec<(usize, usize)>,
    /// Elements in at least one zone, ascending: one geometric stiffness block each.
    covered: Vec<usize>,
    /// The zones containing each element of the mesh (empty outside every zone).
    zones_of_element: Vec<Vec<usize>>,
    /// Outward boundary surface of every zone.
    boundaries: Vec<ElementSurface>,
}

impl ZonalConstraints {
    /// Hard zonal constraints on the 4-node tets of `mesh` (the one-point rule, exact), one
    /// per zone of `zones`.
    ///
    /// Errors: those of [`ZonalConstraints::on_elements`].
    pub fn new(mesh: &TetMesh, zones: &Zones) -> Result<Self, ConstraintError> {
        let linear = ElementMesh::linear(mesh.clone());
        Self::on_elements(&linear, TetQuadrature::Degree1, zones)
    }

    /// Hard zonal constraints on the elements of `mesh`, one per zone of `zones` (sets of
    /// element indices), integrated with `rule` (see [`crate::exact_rule`]).
    ///
    /// Errors: [`ConstraintError::InvalidParameter`] if there are no zones,
    /// [`ConstraintError::InvalidZone`] for an empty zone, an element index outside the mesh,
    /// or a face shared by more than two of the zone's elements.
    pub fn on_elements(
        mesh: &ElementMesh,
        rule: TetQuadrature,
        zones: &Zones,
    ) -> Result<Self, ConstraintError> {
        if zones.is_empty() {
            return Err(ConstraintError::InvalidParameter {
                name: "zones",
                value: 0.0,
                reason: "at least one zone is needed",
            });
        }
        let num_elements = mesh.num_elements();
        let mut zones_of_element = vec![Vec::new(); num_elements];
        let mut entries = Vec::new();
        for (z, zone) in zones.iter().enumerate() {
            if zone.is_empty() {
                return Err(ConstraintError::InvalidZone {
                    zone: z,
                    reason: "the zone has no tets".into(),
                });
            }
            for &e in zone {
                if e >= num_elements {
                    return Err(ConstraintError::InvalidZone {
                        zone: z,
                        reason: format!("tet {e} is not in the mesh ({num_elements} tets)"),
                    });
                }
                zones_of_element[e].push(z);
                entries.push((z, e));
            }
        }
        let elements = MeasuredElements::new(mesh, rule, Measure::Linear)?;
        let zones: Vec<Vec<usize>> = zones.iter().map(<[usize]>::to_vec).collect();
        let rest_zone_volumes = zones
            .iter()
            .map(|zone| zone.iter().map(|&e| elements.rest_volume(e)).sum())
            .collect();
        let boundaries = zones
            .iter()
            .enumerate()
            .map(|(z, zone)| {
                ElementSurface::of_elements(mesh, zone).map_err(|err| {
                    ConstraintError::InvalidZone {
                        zone: z,
                        reason: err.to_string(),
                    }
                })
            })
            .collect::<Result<_, _>>()?;
        Ok(ZonalConstraints {
            elements,
            compliance: vec![0.0; zones.len()],
            covered: (0..num_elements)
                .filter(|&e| !zones_of_element[e].is_empty())
                .collect(),
            zones,
            rest_zone_volumes,
            entries,
            zones_of_element,
            boundaries,
        })
    }

    /// Makes the constraints compliant with bulk modulus `kappa`: `C_j = V_j / kappa` with
    /// `V_j` the rest volume of zone `j` (eq. 18 with one constant pressure per zone).
    /// `f64::INFINITY` keeps them hard.
    ///
    /// Errors: [`ConstraintError::InvalidParameter`] unless `kappa > 0`.
    pub fn with_bulk_modulus(mut self, kappa: f64) -> Result<Self, ConstraintError> {
        let inverse = inverse_bulk_modulus(kappa)?;
        self.compliance = self.rest_zone_volumes.iter().map(|v| v * inverse).collect();
        Ok(self)
    }

    /// Rest volume of every zone, `sum_e sum_q W_q` over its elements.
    pub fn rest_zone_volumes(&self) -> &[f64] {
        &self.rest_zone_volumes
    }

    /// Outward boundary surface of zone `z`: the faces of its elements not shared by two of
    /// its elements ([`ElementSurface::of_elements`]).
    ///
    /// Errors: [`ConstraintError::InvalidZone`] if `z` is not a zone.
    pub fn boundary(&self, z: usize) -> Result<&ElementSurface, ConstraintError> {
        self.boundaries
            .get(z)
            .ok_or_else(|| no_such_zone(z, self.zones.len()))
    }

    /// Deformed volume of zone `z` by quadrature, `sum_e sum_q W_q J_q` over its elements
    /// (exact with [`crate::exact_rule`]: `W_q J_q = w_q det(dx/dxi)`, a polynomial of degree
    /// `3p - 3`).
    ///
    /// Errors: wrong length of `x`, or `z` not a zone.
    pub fn zone_volume(&self, z: usize, x: &[Vec3]) -> Result<f64, ConstraintError> {
        self.elements.check_positions(x)?;
        let zone = self
            .zones
            .get(z)
            .ok_or_else(|| no_such_zone(z, self.zones.len()))?;
        Ok(zone
            .iter()
            .map(|&e| self.elements.deformed_volume(e, x))
            .sum())
    }

    /// Deformed volume of zone `z` from its boundary only (divergence theorem, the
    /// optimization noted after eq. 8; [`ElementSurface::enclosed_volume`], exact on 3- and
    /// 6-node faces). Equal to [`ZonalConstraints::zone_volume`] up to rounding for any `x`
    /// when the rule is exact.
    ///
    /// Errors: wrong length of `x`, or `z` not a zone.
    pub fn zone_boundary_volume(&self, z: usize, x: &[Vec3]) -> Result<f64, ConstraintError> {
        self.elements.check_positions(x)?;
        Ok(self.boundary(z)?.enclosed_volume(x))
    }

    /// The sum of the multipliers of the zones containing element `e`.
    fn element_multiplier(&self, e: usize, multipliers: &[f64]) -> f64 {
        self.zones_of_element[e]
            .iter()
            .map(|&z| multipliers[z])
            .sum()
    }
}

impl ConstraintSet for ZonalConstraints {
    fn name(&self) -> &'static str {
        "zonal"
    }

    fn num_constraints(&self) -> usize {
        self.zones.len()
    }

    fn values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError> {
        self.elements.check_positions(x)?;
        check_len("constraint values", self.zones.len(), out.len())?;
        let mut m = vec![0.0; self.elements.len()];
        self.elements.fill_values(x, RowShape::One, &mut m)?;
        out.par_iter_mut()
            .zip(self.zones.par_iter())
            .for_each(|(c, zone)| *c = zone.iter().map(|&e| m[e]).sum());
        Ok(())
    }

    fn jacobian_pattern(&self) -> Vec<(usize, usize)> {
        self.entries
            .iter()
            .flat_map(|&(z, e)| self.elements.dofs(e).map(move |dof| (z, dof)))
            .collect()
    }

    fn jacobian_values(&self, x: &[Vec3], out: &mut [f64]) -> Result<(), ConstraintError> {
        self.elements.check_positions(x)?;
        self.elements
            .fill_gradients(x, RowShape::One, out, self.entries.len(), |b| {
                self.entries[b].1
            })
    }

    fn geometric_stiffness_pattern(&self) -> Vec<(usize, usize)> {
        self.elements.hessian_pattern(self.covered.iter().copied())
    }

    fn geometric_stiffness_values(
        &self,
        x: &[Vec3],
        multipliers: &[f64],
        out: &mut [f64],
    ) -> Result<(), ConstraintError> {
        self.elements.check_positions(x)?;
        check_len("multipliers", self.zones.len(), multipliers.len())?;
        self.elements.fill_hessians(
            x,
            out,
            self.covered.len(),
            |b| self.covered[b],
            |e, _| self.element_multiplier(e, multipliers),
        )
    }

    fn admits_inversion(&self) -> bool {
        true
    }

    fn compliance(&self) -> Compliance {
        Compliance::Diagonal(self.compliance.clone())
    }

    /// The coarse-scale pressure of Sheen et al. 2021, sec. 8.2: the sum of the multipliers
    /// of the zones containing the element (zero outside every zone). Their per-tet pressure
    /// adds the fine-scale volumetric stress `lambda U'(J)` of the compression penalty; the
    /// penalty belongs to the material model, so the solver adds that term, not this set.
    fn tet_pressures(&self, x: &[Vec3], multipliers: &[f64]) -> Vec<f64> {
        if self.elements.check_positions(x).is_err() {
            return Vec::new();
        }
        if multipliers.len() != self.zones.len() {
            return Vec::new();
        }
        (0..self.elements.len())
            .map(|e| self.element_multiplier(e, multipliers))
            .collect()
    }
}

fn no_such_zone(z: usize, zones: usize) -> ConstraintError {
    ConstraintError::InvalidZone {
        zone: z,
        reason: format!("no such zone ({zones} zones)"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measured::test_meshes::{moved, two_tets};

    #[test]
    fn boundary_of_two_tets_and_its_volume() {
        let mesh = two_tets();
        let zones = Zones::from_sets(vec![vec![0, 1], vec![1]]);
        let set = ZonalConstraints::new(&mesh, &zones).unwrap();
        assert_eq!(set.boundary(0).unwrap().len(), 6);
        assert_eq!(set.boundary(1).unwrap().len(), 4);
        let x = moved(&mesh, 2, Vec3::new(0.2, 0.1, -0.3));
        for z in 0..2 {
            let by_tets = set.zone_volume(z, &x).unwrap();
            let by_faces = set.zone_boundary_volume(z, &x).unwrap();
            assert!((by_tets - by_faces).abs() < 1e-15, "zone {z}");
        }
        let mut c = [1.0; 2];
        set.values(mesh.positions(), &mut c).unwrap();
        assert_eq!(c, [0.0, 0.0]);
        assert_eq!(set.tet_pressures(&x, &[2.0, 5.0]), vec![2.0, 7.0]);
        assert_eq!(set.compliance(), Compliance::Diagonal(vec![0.0, 0.0]));
        let soft = set.with_bulk_modulus(2.0).unwrap();
        let v = mesh.rest_volumes();
        assert_eq!(
            soft.compliance(),
            Compliance::Diagonal(vec![(v[0] + v[1]) / 2.0, v[1] / 2.0])
        );
    }

    #[test]
    fn bad_zones_are_errors() {
        let mesh = two_tets();
        let err = |sets: Vec<Vec<usize>>| ZonalConstraints::new(&mesh, &Zones::from_sets(sets));
        assert!(matches!(
            err(vec![]),
            Err(ConstraintError::InvalidParameter { name: "zones", .. })
        ));
        assert!(matches!(
            err(vec![vec![0], vec![]]),
            Err(ConstraintError::InvalidZone { zone: 1, .. })
        ));
        let e = err(vec![vec![0, 2]]).unwrap_err();
        assert!(e.to_string().contains("tet 2"), "{e}");
        let set = err(vec![vec![0]]).unwrap();
        assert!(set.boundary(1).is_err());
        assert!(set.zone_volume(0, &mesh.positions()[..3]).is_err());
        assert!(set.with_bulk_modulus(-1.0).is_err());
    }
}
