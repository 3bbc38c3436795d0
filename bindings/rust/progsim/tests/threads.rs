//! The process-wide thread count of progsim's parallel loops (`ps_set_threads`). In a binary of
//! its own: the setting is the whole process's, and other tests' threads must not see it move.

use progsim::Status;

#[test]
fn a_fixed_count_is_reported_and_nonsense_is_refused_unchanged() {
    progsim::set_threads(2).unwrap();
    assert_eq!(progsim::threads().unwrap(), (2, 2));
    let err = progsim::set_threads(-1).unwrap_err();
    assert_eq!(err.code(), Status::InvalidArgument);
    assert!(err.message().contains("thread count -1"), "{}", err.message());
    assert_eq!(progsim::set_threads(1025).unwrap_err().code(), Status::InvalidArgument);
    assert_eq!(progsim::threads().unwrap().0, 2);
    progsim::set_threads(0).unwrap();
    let (setting, current) = progsim::threads().unwrap();
    assert_eq!(setting, 0);
    assert!(current >= 1);
}
