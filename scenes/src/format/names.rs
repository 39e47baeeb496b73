//! The names a scene chooses from: every `*Name` type of the format, each parsed by its one
//! [`FromStr`], which serde and the command line both go through.

use isochor_mesh::element::TetElement;
use isochor_mesh::io::VtuEncoding;
use isochor_solvers::{MaterialModel, Method, ModelInfo};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;
use std::str::FromStr;

/// A name that is not one of a closed set, with the valid ones.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownName {
    /// The name given.
    pub given: String,
    /// The valid names.
    pub valid: &'static [&'static str],
}

impl fmt::Display for UnknownName {
    /// In serde's words for an unknown enum value, so that both spellings read alike.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let quoted: Vec<String> = self.valid.iter().map(|n| format!("`{n}`")).collect();
        let expected = match quoted.as_slice() {
            [one] => one.clone(),
            [a, b] => format!("{a} or {b}"),
            all => format!("one of {}", all.join(", ")),
        };
        write!(f, "unknown value `{}`, expected {expected}", self.given)
    }
}

impl std::error::Error for UnknownName {}

/// Deserializes a name through its [`FromStr`].
fn deserialize_name<'de, D, T>(d: D) -> Result<T, D::Error>
where
    D: Deserializer<'de>,
    T: FromStr,
    T::Err: fmt::Display,
{
    String::deserialize(d)?
        .parse()
        .map_err(serde::de::Error::custom)
}

/// A closed set of names: the enum, its `ALL`, `NAMES` and `name()`, one `FromStr`, and serde
/// through them.
macro_rules! names {
    (
        $(#[$meta:meta])*
        pub enum $ty:ident {
            $( $(#[$vmeta:meta])* $variant:ident = $name:literal, )+
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub enum $ty {
            $( $(#[$vmeta])* $variant, )+
        }

        impl $ty {
            /// Every value, in the order of [`Self::NAMES`].
            pub const ALL: &'static [$ty] = &[$($ty::$variant,)+];
            /// The names as scenes write them.
            pub const NAMES: &'static [&'static str] = &[$($name,)+];

            /// The name as scenes write it.
            pub fn name(self) -> &'static str {
                match self {
                    $($ty::$variant => $name,)+
                }
            }
        }

        impl FromStr for $ty {
            type Err = UnknownName;
            fn from_str(s: &str) -> Result<Self, UnknownName> {
                match s {
                    $($name => Ok($ty::$variant),)+
                    _ => Err(UnknownName { given: s.to_string(), valid: Self::NAMES }),
                }
            }
        }

        impl fmt::Display for $ty {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.name())
            }
        }

        impl Serialize for $ty {
            fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_str(self.name())
            }
        }

        impl<'de> Deserialize<'de> for $ty {
            fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                deserialize_name(d)
            }
        }
    };
}

/// A method name, parsed by [`Method`]'s `FromStr` (see [`Method::ALL`] for the names).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MethodName(pub Method);

impl FromStr for MethodName {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        s.parse::<Method>()
            .map(MethodName)
            .map_err(|e| e.to_string())
    }
}

/// An element name, `"tet4"` or `"tet10"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ElementName(pub TetElement);

impl Default for ElementName {
    fn default() -> Self {
        ElementName(TetElement::Tet4)
    }
}

impl FromStr for ElementName {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        TetElement::from_name(s).map(ElementName).ok_or_else(|| {
            let valid: Vec<&str> = TetElement::ALL.iter().map(|e| e.name()).collect();
            format!("unknown element '{s}' (valid: {})", valid.join(", "))
        })
    }
}

/// Serde of the newtype names, through their `FromStr` and the wrapped type's name.
macro_rules! newtype_serde {
    ($ty:ident) => {
        impl Serialize for $ty {
            fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_str(self.0.name())
            }
        }

        impl<'de> Deserialize<'de> for $ty {
            fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                deserialize_name(d)
            }
        }
    };
}

newtype_serde!(MethodName);
newtype_serde!(ElementName);

/// `material.model`: a model of the solver's catalogue ([`MaterialModel::ALL`]), parsed by
/// its name.
#[derive(Debug, Clone, Copy)]
pub struct ModelName(pub &'static ModelInfo);

impl ModelName {
    /// The default model, `neo-hookean`.
    pub fn neo_hookean() -> ModelName {
        ModelName(&MaterialModel::ALL[0])
    }

    /// The name as scenes write it.
    pub fn name(self) -> &'static str {
        self.0.name
    }
}

impl PartialEq for ModelName {
    fn eq(&self, other: &Self) -> bool {
        self.0.name == other.0.name
    }
}

impl Eq for ModelName {}

impl FromStr for ModelName {
    type Err = UnknownName;
    fn from_str(s: &str) -> Result<Self, UnknownName> {
        MaterialModel::info(s).map(ModelName).ok_or(UnknownName {
            given: s.to_string(),
            valid: MaterialModel::NAMES,
        })
    }
}

impl Serialize for ModelName {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for ModelName {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        deserialize_name(d)
    }
}

names! {
    /// `material.kappa`: the volumetric stiffness of the mixed methods.
    pub enum KappaName {
        /// The bulk modulus (the default).
        Bulk = "bulk",
        /// The first Lame parameter.
        Lambda = "lambda",
    }
}

names! {
    /// `material.zonal_energy`.
    pub enum ZonalEnergyName {
        /// F-bar deviatoric neo-Hookean plus `zonal_penalty U(J; beta)` (the default).
        Constrained = "constrained",
        /// The standard coupled neo-Hookean.
        Standard = "standard",
    }
}

names! {
    /// `zones.kind`: the zone layout.
    pub enum ZoneKind {
        /// One zone holding every tet.
        Global = "global",
        /// Overlapping k-ring zones covering the mesh.
        KRing = "k-ring",
        /// Zones painted on the surface (labels of the scene).
        Painted = "painted",
        /// No zone: the zonal energy (`zonal_penalty U(J; beta)` under the F-bar energy)
        /// alone holds the volume, "ours without volume constraint" of Table 1 of Sheen et
        /// al. 2021. An error with `zonal_penalty = 0`, which leaves the volume free.
        None = "none",
    }
}

names! {
    /// `solver.linear`: the linear solver.
    pub enum LinearName {
        /// Sparse direct factorization.
        Direct = "direct",
        /// CG or MINRES.
        Iterative = "iterative",
        /// Direct for small systems, iterative for large ones.
        Auto = "auto",
    }
}

names! {
    /// `solver.linear_preconditioner`: the preconditioner of the iterative linear solver.
    pub enum PreconditionerName {
        /// Diagonal scaling.
        Jacobi = "jacobi",
        /// Zero-fill incomplete Cholesky.
        IncompleteCholesky = "incomplete-cholesky",
        /// Smoothed-aggregation algebraic multigrid.
        Multigrid = "multigrid",
    }
}

names! {
    /// `solver.jacobian`: the matrix of each Newton iteration.
    pub enum JacobianName {
        /// Assembled and factorized every iteration.
        Full = "full",
        /// The last factorization reused while the residual halves (modified Newton).
        Modified = "modified",
    }
}

names! {
    /// `solver.ordering`: the fill-reducing ordering.
    pub enum OrderingName {
        /// Approximate minimum degree.
        Amd = "amd",
        /// Nested dissection (METIS).
        NestedDissection = "nested-dissection",
        /// By size (see `isochor_solvers::linear::Ordering::AUTO_THRESHOLD`).
        Auto = "auto",
    }
}

names! {
    /// A unit of length for showing a probe.
    pub enum LengthUnit {
        /// Metres.
        Metre = "m",
        /// Centimetres.
        Centimetre = "cm",
        /// Millimetres.
        Millimetre = "mm",
    }
}

impl LengthUnit {
    /// The unit's symbol.
    pub fn symbol(self) -> &'static str {
        self.name()
    }

    /// A length in metres, in this unit.
    pub fn from_metres(self, metres: f64) -> f64 {
        match self {
            LengthUnit::Metre => metres,
            LengthUnit::Centimetre => 100.0 * metres,
            LengthUnit::Millimetre => 1000.0 * metres,
        }
    }
}

names! {
    /// A vector component a probe reads.
    pub enum ComponentName {
        /// The x component.
        X = "x",
        /// The y component.
        Y = "y",
        /// The z component.
        Z = "z",
        /// The length.
        Norm = "norm",
    }
}

names! {
    /// How a probe reduces over a selection or the steps of a run.
    #[derive(Default)]
    pub enum Reduce {
        /// The mean (the default).
        #[default]
        Mean = "mean",
        /// The largest value.
        Max = "max",
        /// The smallest value.
        Min = "min",
    }
}

names! {
    /// An energy a probe reads.
    pub enum EnergyName {
        /// Kinetic energy.
        Kinetic = "kinetic",
        /// Stored elastic energy.
        Elastic = "elastic",
        /// Potential of the external loads.
        External = "external",
        /// Energy of the compliant volume constraints (the mixed methods' volumetric energy).
        Constraint = "constraint",
        /// Elastic, constraint and external: the total potential energy.
        Potential = "potential",
        /// Kinetic plus potential.
        Total = "total",
    }
}

names! {
    /// `output.preview_field`: what colors the preview, with the values of the VTU frames'
    /// field of that name.
    #[derive(Default)]
    pub enum PreviewField {
        /// Length of the node displacement, averaged over the nodes of each drawn triangle.
        #[default]
        Displacement = "displacement",
        /// Von Mises stress of the tet behind each boundary face.
        VonMises = "von_mises",
        /// Mean stress `tr(sigma)/3` (tension positive) of the tet behind each boundary face.
        MeanStress = "mean_stress",
        /// Volume ratio of the tet behind each boundary face.
        J = "J",
    }
}

names! {
    /// `output.vtu_encoding`: how the VTU frames store their arrays.
    #[derive(Default)]
    pub enum VtuEncodingName {
        /// Binary for meshes of at least [`VtuEncodingName::AUTO_BINARY_NODES`] nodes, ASCII
        /// below (small outputs stay readable as text).
        #[default]
        Auto = "auto",
        /// zlib-compressed appended binary.
        Binary = "binary",
        /// Text.
        Ascii = "ascii",
    }
}

impl VtuEncodingName {
    /// Nodes from which `auto` writes binary frames.
    pub const AUTO_BINARY_NODES: usize = 10_000;

    /// The encoding of the frames of a mesh of `nodes` nodes.
    pub fn resolve(self, nodes: usize) -> VtuEncoding {
        match self {
            VtuEncodingName::Binary => VtuEncoding::Binary,
            VtuEncodingName::Ascii => VtuEncoding::Ascii,
            VtuEncodingName::Auto if nodes >= Self::AUTO_BINARY_NODES => VtuEncoding::Binary,
            VtuEncodingName::Auto => VtuEncoding::Ascii,
        }
    }
}

names! {
    /// `output.points`: the points of the VTU frames.
    #[derive(Default)]
    pub enum PointsName {
        /// The rest positions, with the point field `displacement` to warp them by (ParaView's
        /// Warp By Vector shows the deformed body; the default).
        #[default]
        Rest = "rest",
        /// The deformed positions (the `displacement` field then shows how far each point
        /// moved; warping by it doubles the deformation).
        Deformed = "deformed",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn auto_encoding_is_binary_from_ten_thousand_nodes() {
        let auto = VtuEncodingName::Auto;
        assert_eq!(auto.resolve(9_999), VtuEncoding::Ascii);
        assert_eq!(auto.resolve(10_000), VtuEncoding::Binary);
        assert_eq!(VtuEncodingName::Ascii.resolve(1 << 20), VtuEncoding::Ascii);
        assert_eq!(VtuEncodingName::Binary.resolve(4), VtuEncoding::Binary);
    }

    #[test]
    fn every_name_parses_back() {
        for name in MaterialModel::NAMES {
            assert_eq!(name.parse::<ModelName>().map(ModelName::name), Ok(*name));
        }
        assert_eq!(ModelName::neo_hookean().name(), "neo-hookean");
        let e = "inch".parse::<LengthUnit>().unwrap_err().to_string();
        assert_eq!(e, "unknown value `inch`, expected one of `m`, `cm`, `mm`");
        let e = "x".parse::<KappaName>().unwrap_err().to_string();
        assert_eq!(e, "unknown value `x`, expected `bulk` or `lambda`");
    }
}
