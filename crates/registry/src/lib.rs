//! One registry type for everything friction-lab finds by name — solvers, rigs, the rows of
//! Table 2 — holding the built-in entries and those a user registers while the program runs.
//!
//! A [`Registry`] is a `static`: a fixed list of built-ins ([`Registry::new`]) and a list of
//! registered entries behind a lock. Every lookup by name ([`Registry::get`], the `FromStr` of a
//! handle) and every listing ([`Registry::all`], [`Registry::names`]) searches both, built-ins
//! first, so that a user's entry is found wherever a built-in one is: on the command line's
//! library call, in Python, in a study.
//!
//! A handle ([`handle!`]) is a `Copy` reference to a `'static` entry (a solver's
//! `OneStepMethod`, a rig's `Rig`) with whether it is a user's own: it dereferences to the
//! entry, shows and serialises as its name, and parses from a name through its registry.

use std::sync::RwLock;

/// An entry a [`Registry`] holds: anything with a name.
pub trait Named: Clone + 'static {
    /// The name a lookup finds it by.
    fn name(&self) -> &str;
}

/// The built-in entries of one kind and those registered at run time.
pub struct Registry<H: 'static> {
    /// What one entry is called in messages (`solver`).
    noun: &'static str,
    /// What several are called (`solvers`).
    plural: &'static str,
    /// The built-in entries, in listing order.
    built_ins: &'static [H],
    /// The entries registered while the program runs, in the order they were first
    /// registered.
    registered: RwLock<Vec<H>>,
}

impl<H: Named> Registry<H> {
    /// A registry of the `built_ins`, whose entries messages call `noun` (several: `plural`).
    pub const fn new(noun: &'static str, plural: &'static str, built_ins: &'static [H]) -> Self {
        Registry {
            noun,
            plural,
            built_ins,
            registered: RwLock::new(Vec::new()),
        }
    }

    /// The built-in entries, in listing order.
    pub fn built_ins(&self) -> &'static [H] {
        self.built_ins
    }

    /// Every entry: the built-ins in listing order, then the registered ones in the order
    /// they were registered.
    pub fn all(&self) -> Vec<H> {
        let registered = self.registered.read().unwrap_or_else(|e| e.into_inner());
        self.built_ins
            .iter()
            .chain(registered.iter())
            .cloned()
            .collect()
    }

    /// The names of [`Registry::all`].
    pub fn names(&self) -> Vec<String> {
        self.all().iter().map(|h| h.name().to_string()).collect()
    }

    /// The entry called `name`, built in or registered.
    pub fn find(&self, name: &str) -> Option<H> {
        if let Some(h) = self.built_ins.iter().find(|h| h.name() == name) {
            return Some(h.clone());
        }
        let registered = self.registered.read().unwrap_or_else(|e| e.into_inner());
        registered.iter().find(|h| h.name() == name).cloned()
    }

    /// The entry called `name`, or a message naming every entry there is:
    /// "unknown solver `x`; known solvers: rk4, dopri5, …".
    pub fn get(&self, name: &str) -> Result<H, String> {
        self.find(name).ok_or_else(|| {
            format!(
                "unknown {} `{name}`; known {}: {}",
                self.noun,
                self.plural,
                self.names().join(", ")
            )
        })
    }

    /// Registers `entry` under its name, so that every lookup finds it; an entry registered
    /// before under the same name is replaced. Refused (with the reason) when the name is
    /// not a non-empty word without commas, or a built-in entry has it.
    pub fn register(&self, entry: H) -> Result<H, String> {
        let name = entry.name();
        if name.trim().is_empty() || name.contains(',') || name.contains(char::is_whitespace) {
            return Err(format!(
                "a {}'s name must be a non-empty word without commas, not {name:?}",
                self.noun
            ));
        }
        if self.built_ins.iter().any(|h| h.name() == name) {
            return Err(format!(
                "a {} cannot be named `{name}`: a built-in {} has that name; choose another name",
                self.noun, self.noun
            ));
        }
        let mut registered = self.registered.write().unwrap_or_else(|e| e.into_inner());
        match registered.iter_mut().find(|h| h.name() == name) {
            Some(old) => *old = entry.clone(),
            None => registered.push(entry.clone()),
        }
        Ok(entry)
    }
}

/// A `Copy` reference to a `'static` entry of type `T`, and whether it is a user's own: what a
/// handle ([`handle!`]) wraps.
pub struct Entry<T: ?Sized + 'static> {
    item: &'static T,
    own: bool,
}

impl<T: ?Sized> Entry<T> {
    /// A built-in entry.
    pub const fn built_in(item: &'static T) -> Self {
        Entry { item, own: false }
    }

    /// A user's own entry.
    pub const fn own(item: &'static T) -> Self {
        Entry { item, own: true }
    }

    /// The entry.
    pub const fn item(&self) -> &'static T {
        self.item
    }

    /// Whether it is a user's own.
    pub const fn is_own(&self) -> bool {
        self.own
    }
}

impl<T: ?Sized> Clone for Entry<T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T: ?Sized> Copy for Entry<T> {}

/// Defines a handle: a `Copy` newtype over an [`Entry`] of a trait object, found by name in a
/// [`Registry`] of handles.
///
/// `handle!(Solver => dyn OneStepMethod, SOLVERS)` defines `pub struct Solver`, which
/// dereferences to the `dyn OneStepMethod`; has `built_in`, `own`, `name`, `is_own`,
/// `from_name` (through `SOLVERS`), `all` and `register`; shows and serialises as its name
/// (`own NAME` in `Debug`); and parses from a name. Two handles are equal when both are
/// built in or both a user's own and they have the same name: a user's entry is never equal
/// to a built-in one. The trait must have `fn name(&self) -> &'static str`.
#[macro_export]
macro_rules! handle {
    ($(#[$doc:meta])* $handle:ident => $item:ty, $registry:path) => {
        $(#[$doc])*
        #[derive(Clone, Copy)]
        pub struct $handle($crate::Entry<$item>);

        impl $handle {
            /// A built-in entry.
            pub const fn built_in(item: &'static $item) -> Self {
                $handle($crate::Entry::built_in(item))
            }

            /// An entry of the user's own, run wherever a built-in one is; registered
            /// ([`Self::register`]), it is also found by its name.
            pub const fn own(item: &'static $item) -> Self {
                $handle($crate::Entry::own(item))
            }

            /// The name it is found by.
            pub fn name(self) -> &'static str {
                self.0.item().name()
            }

            /// Whether it is a user's own.
            pub fn is_own(self) -> bool {
                self.0.is_own()
            }

            /// The entry called `name`, built in or registered.
            pub fn from_name(name: &str) -> Result<Self, String> {
                $registry.get(name)
            }

            /// Every entry, built in and registered, in listing order.
            pub fn all() -> Vec<Self> {
                $registry.all()
            }

            /// Registers `item` as the user's own under its name ([`$crate::Registry::register`]).
            pub fn register(item: &'static $item) -> Result<Self, String> {
                $registry.register($handle::own(item))
            }
        }

        impl $crate::Named for $handle {
            fn name(&self) -> &str {
                self.0.item().name()
            }
        }

        impl std::ops::Deref for $handle {
            type Target = $item;
            fn deref(&self) -> &Self::Target {
                self.0.item()
            }
        }

        /// A built-in entry shows as its name, an own one as `own NAME`.
        impl std::fmt::Debug for $handle {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                if self.is_own() {
                    f.write_str("own ")?;
                }
                f.write_str(self.name())
            }
        }

        impl std::fmt::Display for $handle {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl PartialEq for $handle {
            fn eq(&self, other: &Self) -> bool {
                self.is_own() == other.is_own() && self.name() == other.name()
            }
        }

        impl Eq for $handle {}

        impl std::hash::Hash for $handle {
            fn hash<S: std::hash::Hasher>(&self, state: &mut S) {
                self.is_own().hash(state);
                self.name().hash(state);
            }
        }

        /// Written as its name.
        impl $crate::serde::Serialize for $handle {
            fn serialize<S: $crate::serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_str(self.name())
            }
        }

        impl std::str::FromStr for $handle {
            type Err = String;
            fn from_str(s: &str) -> Result<Self, String> {
                $handle::from_name(s)
            }
        }
    };
}

#[doc(hidden)]
pub use serde;

#[cfg(test)]
mod tests {
    use super::*;

    /// A thing with a name, for the tests.
    pub trait Thing: Sync {
        fn name(&self) -> &'static str;
    }

    pub struct Called(&'static str);

    impl Thing for Called {
        fn name(&self) -> &'static str {
            self.0
        }
    }

    handle!(
        /// A thing of the test registry.
        Handle => dyn Thing, THINGS
    );

    static THINGS: Registry<Handle> = Registry::new(
        "thing",
        "things",
        &[
            Handle::built_in(&Called("a")),
            Handle::built_in(&Called("b")),
        ],
    );

    #[test]
    fn a_registered_entry_is_found_and_listed_after_the_built_ins() {
        let e = "c".parse::<Handle>().unwrap_err();
        assert_eq!(e, "unknown thing `c`; known things: a, b");
        static C: Called = Called("c");
        let c = Handle::register(&C).unwrap();
        assert_eq!("c".parse::<Handle>().unwrap(), c);
        assert_eq!(THINGS.names(), ["a", "b", "c"]);
        assert_eq!(format!("{c:?} {c}"), "own c c");
        // An own entry is never equal to a built-in one of the same name, and a built-in's
        // name cannot be registered.
        static A: Called = Called("a");
        assert_ne!(Handle::own(&A), Handle::from_name("a").unwrap());
        let e = Handle::register(&A).unwrap_err();
        assert!(e.contains("a built-in thing has that name"), "{e}");
        static BAD: Called = Called("x,y");
        assert!(Handle::register(&BAD)
            .unwrap_err()
            .contains("without commas"));
        // Registering a name again replaces the entry, keeping its place.
        static C2: Called = Called("c");
        Handle::register(&C2).unwrap();
        assert_eq!(Handle::all().len(), 3);
        assert_eq!(c.name(), "c");
        assert!(std::ptr::eq(
            Handle::from_name("c").unwrap().0.item() as *const dyn Thing as *const u8,
            &C2 as *const Called as *const u8
        ));
    }
}
