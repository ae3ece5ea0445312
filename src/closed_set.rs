//! The one way a family of variants is put together (shapes, BSDFs, lights and texture
//! patterns): [`closed_set!`] declares the family's trait, the enum of its variants, and the
//! trait for the enum forwarding each method to the variant inside, so a family's variants
//! are matched in one place and adding one is its file plus one line in the enum.
//!
//! Static dispatch: the enum's methods are one `match` each, inlined, as hand-written arms
//! would be; no trait objects.

/// Declares a closed set: a trait, an enum whose every variant holds one type implementing
/// it, the trait's methods on the enum (as inherent methods, so callers need not import the
/// trait, each one `match` forwarding to the variant inside), the trait for the enum, and
/// `From` each variant's type.
///
/// ```
/// snell::closed_set! {
///     /// Something with an area.
///     pub trait Area {
///         /// The area.
///         fn area(&self) -> f32;
///         /// The area of `n` of them (a default the variants may keep).
///         fn of(&self, n: f32) -> f32 { self.area() * n }
///     }
///     /// Every shape with an area.
///     #[derive(Clone, Copy, Debug)]
///     pub enum Flat {
///         /// A square.
///         Square(Square),
///     }
/// }
/// /// A unit square.
/// #[derive(Clone, Copy, Debug)]
/// pub struct Square;
/// impl Area for Square {
///     fn area(&self) -> f32 { 1.0 }
/// }
/// assert_eq!(Flat::from(Square).of(3.0), 3.0);
/// ```
///
/// Each method takes `&self` and named arguments and returns a value; one with a body is a
/// default that variants may keep. The enum's methods are `#[inline]` and as visible as
/// the enum.
#[macro_export]
macro_rules! closed_set {
    (
        $(#[$trait_meta:meta])*
        $trait_vis:vis trait $trait:ident {
            $(
                $(#[$method_meta:meta])*
                fn $method:ident(&$self:ident $(, $arg:ident : $arg_ty:ty)* $(,)?) -> $ret:ty
                $({ $($default:tt)* })? $(;)?
            )*
        }
        $(#[$enum_meta:meta])*
        $enum_vis:vis enum $enum:ident {
            $( $(#[$variant_meta:meta])* $variant:ident($variant_ty:ty) ),* $(,)?
        }
    ) => {
        $(#[$trait_meta])*
        $trait_vis trait $trait {
            $(
                $crate::closed_set!(@declare
                    $(#[$method_meta])*
                    fn $method(&$self $(, $arg: $arg_ty)*) -> $ret $({ $($default)* })?
                );
            )*
        }

        $(#[$enum_meta])*
        $enum_vis enum $enum {
            $( $(#[$variant_meta])* $variant($variant_ty), )*
        }

        $crate::closed_set!(@impl $enum_vis $enum $trait inner [$($variant)*]
            $([$(#[$method_meta])* fn $method(&self $(, $arg: $arg_ty)*) -> $ret
                => (inner $(, $arg)*)])*
        );

        $(
            impl From<$variant_ty> for $enum {
                fn from(inner: $variant_ty) -> Self {
                    $enum::$variant(inner)
                }
            }
        )*
    };

    (@declare $(#[$meta:meta])* fn $method:ident(&$self:ident $(, $arg:ident : $arg_ty:ty)*)
        -> $ret:ty { $($default:tt)* }) => {
        $(#[$meta])*
        #[allow(unused_variables)]
        fn $method(&$self $(, $arg: $arg_ty)*) -> $ret { $($default)* }
    };
    (@declare $(#[$meta:meta])* fn $method:ident(&$self:ident $(, $arg:ident : $arg_ty:ty)*)
        -> $ret:ty) => {
        $(#[$meta])*
        fn $method(&$self $(, $arg: $arg_ty)*) -> $ret;
    };

    (@impl $enum_vis:vis $enum:ident $trait:ident $inner:ident $variants:tt
        $([$(#[$meta:meta])* fn $method:ident $($rest:tt)*])*) => {
        impl $enum {
            $( $crate::closed_set!(@forward $enum_vis $enum $inner $variants
                $(#[$meta])* fn $method $($rest)*); )*
        }

        impl $trait for $enum {
            $( $crate::closed_set!(@delegate $enum fn $method $($rest)*); )*
        }
    };

    (@forward $vis:vis $enum:ident $inner:ident [$($variant:ident)*] $(#[$meta:meta])*
        fn $method:ident(&self $(, $arg:ident : $arg_ty:ty)*) -> $ret:ty => $call:tt) => {
        $(#[$meta])*
        #[inline]
        $vis fn $method(&self $(, $arg: $arg_ty)*) -> $ret {
            match self {
                $( $enum::$variant($inner) => $crate::closed_set!(@call $method $call), )*
            }
        }
    };

    (@delegate $enum:ident
        fn $method:ident(&self $(, $arg:ident : $arg_ty:ty)*) -> $ret:ty => $call:tt) => {
        #[inline]
        fn $method(&self $(, $arg: $arg_ty)*) -> $ret {
            $enum::$method(self $(, $arg)*)
        }
    };

    (@call $method:ident ($inner:ident $(, $arg:ident)*)) => {
        $inner.$method($($arg),*)
    };
}
