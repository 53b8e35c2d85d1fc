//! The CASC colored complex: a Hasse diagram with user data typed per dimension.
