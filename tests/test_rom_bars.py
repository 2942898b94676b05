"""The ROM's error bars pair each resonance with its own counterpart in a variant.

The truncation variant keeps one more pillar mode; on a tower its second bending
mode (~18 rad/s on nrel5mw) falls below the rotor's own resonance (~111 rad/s), and
pairing by index once printed the rotor's resonance as 110.8 +- 93 rad/s.  The
alignment keeps the order and skips the variant's surplus where it costs least.
"""

from rotorpillar.analysis.rom import _aligned


def test_equal_counts_pair_by_order():
    assert _aligned([2.0, 110.8], [2.01, 110.7]) == [0, 1]


def test_an_inserted_mode_is_skipped_where_it_falls():
    # nrel5mw's case: the tower's second mode between the first and the rotor's
    assert _aligned([2.031, 110.84], [2.031, 17.9, 110.9]) == [0, 2]
    # the paper's case: the extra mode above the rotor's (a higher bending mode)
    assert _aligned([14.9, 27.1], [14.9, 27.1, 155.9]) == [0, 1]
    # below all of them
    assert _aligned([14.9, 27.1], [0.5, 14.9, 27.1]) == [1, 2]


def test_a_variant_with_fewer_modes_leaves_the_last_unpaired():
    assert _aligned([1.0, 2.0, 3.0], [1.0, 2.0]) == [0, 1, None]
