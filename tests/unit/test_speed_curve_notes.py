"""Speed-curve notes (pipeline/speed_curve._notes): with pitch deviations or runout a level
shorter than the hunting period sees other tooth combinations up than down."""

from gearcli.case.load import load_case
from gearcli.pipeline.speed_curve import DWELL_CYCLES, MEASURE_FRACTION, _notes


def test_pitch_errors_shorter_than_the_hunting_period_are_noted():
    assert _notes(load_case("cases/seed.yaml").case) == []
    case = load_case("cases/seed.yaml", ["errors.pitch_deviation.pinion={iso1328_grade: 6}"]).case
    notes = _notes(case)
    # seed 17/25: hunting period lcm = 425 mesh cycles > 0.5 x 150 = 75 measured
    assert MEASURE_FRACTION * DWELL_CYCLES < 425
    assert len(notes) == 1 and "every 425 mesh cycles" in notes[0]
