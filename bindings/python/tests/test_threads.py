"""The process-wide thread count of progsim's parallel loops (``ps_set_threads``)."""

import pytest

import progsim


def test_a_fixed_count_is_reported_and_nonsense_is_refused_unchanged():
    try:
        progsim.set_threads(2)
        assert progsim.threads() == (2, 2)
        with pytest.raises(progsim.InvalidArgumentError, match="thread count -1"):
            progsim.set_threads(-1)
        with pytest.raises(progsim.InvalidArgumentError, match="1 to 1024"):
            progsim.set_threads(5000)
        with pytest.raises(progsim.InvalidArgumentError):
            progsim.set_threads(2**40)  # does not fit int32_t
        assert progsim.threads()[0] == 2
    finally:
        progsim.set_threads(0)
    setting, current = progsim.threads()
    assert setting == 0 and current >= 1
