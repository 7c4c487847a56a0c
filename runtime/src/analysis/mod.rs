//! Analyses of methods on a model: where each stops being stable ([`stability`]) and how much
//! accuracy each buys for how much work ([`work_precision`]).

pub mod stability;
pub mod work_precision;
