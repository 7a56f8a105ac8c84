"""TranslationEngine / ServoPIDController attribute semantics, checked against values printed by
YADE 2023.02a (yade -n -x with the same statements)."""
import pytest

from yade import wrapper


def test_translation_axis_constructor_normalizes_twice():
    # YADE: TranslationEngine(translationAxis=(1,1,0)).translationAxis[0] -> 0.7071067811865476
    e = wrapper.TranslationEngine(translationAxis=(1, 1, 0))
    assert repr(e.translationAxis[0]) == '0.7071067811865476'
    # YADE: e = TranslationEngine(); e.translationAxis = (1,1,0) -> 0.7071067811865475
    e = wrapper.TranslationEngine()
    e.translationAxis = (1, 1, 0)
    assert repr(e.translationAxis[0]) == '0.7071067811865475'
    # YADE: (3,4,0) -> 0.6 ; (1,2,3) -> 0.2672612419124244 either way
    assert wrapper.TranslationEngine(translationAxis=(3, 4, 0)).translationAxis[0] == 0.6
    assert repr(wrapper.TranslationEngine(translationAxis=(1, 2, 3)).translationAxis[0]) == '0.2672612419124244'


def test_servo_defaults_and_unsupported_combination():
    s = wrapper.ServoPIDController()
    assert s.maxVelocity == 0.0 and s.iterPeriod == 100 and s.iterPrevStart == -1 and s.target == 0.0
    c = s + wrapper.TranslationEngine()  # YADE: a CombinedKinematicEngine with the servo's ids
    assert type(c).__name__ == 'CombinedKinematicEngine' and c.comb[0] is s
    with pytest.raises(ValueError, match='negative body id'):
        wrapper.ServoPIDController(ids=[-1])
