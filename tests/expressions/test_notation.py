"""A model's names as a textbook writes them (issue 20 §2): what a student reads has no code."""

import unicodedata

import pytest

from mechgrade.expressions.notation import coordinate_names, textbook, textbook_html


def test_rates_are_dotted_and_greek_names_are_letters():
    assert textbook("thetad*omega + xdd - Abs(y1d)") == "θ̇·ω + ẍ - |ẏ₁|"


def test_a_subscript_is_set_as_one_in_html_and_in_unicode_where_it_has_the_characters():
    assert textbook_html("F_P + mu_k*N_P") == "F<sub>P</sub> + μ<sub>k</sub>·N<sub>P</sub>"
    assert textbook("mu_k*m1") == "μₖ·m₁"


def test_units_are_written_with_middle_dots_and_raised_powers():
    assert textbook("0.72 kg*m^2", rates=False) == "0.72 kg·m²"


def test_a_unit_after_its_number_is_no_symbol():
    assert textbook("0.25 g0") == "0.25 g0"
    assert textbook("g0*t") == "g₀·t"


def test_prose_keeps_its_words_and_dots_the_rates_of_its_formulas():
    sentence = "add the odd term to block1's tension and "
    assert textbook(sentence + "N.y", rates=False) == sentence + "n-hat y"
    assert textbook("so m*xdd = m*g: wrong", rates=False) == "so m·ẍ = m·g: wrong"


def test_a_call_keeps_its_name_and_html_is_escaped():
    assert textbook_html("omega_n(k) < 1 & b_1") == "omega_n(k) &lt; 1 &amp; b<sub>1</sub>"


def test_a_greek_letter_after_a_number_is_a_symbol_not_a_unit():
    assert textbook("2 omega x v") == "2 ω x v"


def test_a_page_writes_a_frames_unit_vector_as_its_equations_do():
    # the bold lower-case letter with a hat, the axis its subscript (mechanics.derivation's)
    assert textbook_html("rod: N.x force balance", False) == "rod: 𝐧̂<sub>x</sub> force balance"
    assert textbook_html("T*A.y") == "T·𝐚̂<sub>y</sub>"
    # not a unit, an abbreviation, a lower-case name or a longer one
    for kept in ("0.5 N.m", "e.g. x.y", "block1.y", "NN.y"):
        assert textbook_html(kept, False) == kept
        assert textbook(kept, False) == kept


def test_plain_text_says_a_frames_unit_vector_in_words():
    # an aria-label, a Markdown page: no hat to set, so as it is read out
    assert textbook("T*N.y") == "T·n-hat y"
    assert textbook("s1 . -A.x", False) == "s₁ . -a-hat x"


def test_a_coordinate_named_by_a_letter_and_a_point_reads_as_the_points_subscript():
    names = coordinate_names(["x", "xj", "yA", "st", "theta2", "thetaB"], ["O", "J"])
    assert names == (("xj", "x_J"), ("yA", "y_A"), ("st", "s_t"), ("thetaB", "theta_B"))
    assert textbook_html("k1*xjd + xj'' - xjdd*yAd + stdd", True, names) == \
        "k<sub>1</sub>·ẋ<sub>J</sub> + ẍ<sub>J</sub> - ẍ<sub>J</sub>·ẏ<sub>A</sub> + s̈<sub>t</sub>"
    assert textbook("xj = 2 m, xjd", True, names) == "x J = 2 m, ẋ J"
    # without the problem's names a word is a word (the notation has no global mode)
    assert textbook_html("xjd") == "xjd"
    # in prose a name stays a word unless it is one of the coordinates
    assert textbook("first stop", False, names) == "first stop"


@pytest.mark.slow
def test_every_coordinate_of_the_library_and_its_rates_read_with_dots():
    # a rate left undotted (xjd) is the model's name showing through: none in any problem
    from mechgrade.resources import shipped_dir
    from mechgrade.solve.worked import problem_names
    from mechgrade.spec import load_problem

    for path in sorted(shipped_dir("problems").glob("*.yaml")):
        problem = load_problem(path)
        names = problem_names(problem)
        for c in problem.coordinates:
            for rate, mark in (("d", "\u0307"), ("dd", "\u0308")):
                for shown in (textbook_html(c.name + rate, True, names),
                              textbook(c.name + rate, True, names)):
                    assert mark in unicodedata.normalize("NFD", shown), (path.name, c.name, shown)
                    assert c.name not in shown or len(c.name) == 1, (path.name, shown)
