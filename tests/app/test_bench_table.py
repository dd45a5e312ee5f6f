"""`sward bench` prints each row's figures: times to a tenth, and small figures (FLIP, shares)
with their digits rather than as 0.0."""

from app.bench import _figure


def test_small_figures_keep_their_digits_and_times_their_tenths():
    assert _figure(0.0004) == "0.0004"
    assert _figure(0.0121) == "0.0121"
    assert _figure(1.54) == "1.54"
    assert _figure(476.3) == "476.3"
    assert _figure(12345.6) == "12,345.6"
