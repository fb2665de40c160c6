"""Reference solutions of the course's exercises and answer keys of its end-of-chapter questions, one module per
notebook: ``ch01`` (tagging by the guidelines) ... ``ch07`` (instructions of your own).

Reference solutions: try the exercise first. Each notebook's exercise cell holds a stub for you to fill in, and
its check says what is right or wrong in your answer; come here when you are stuck or done, to compare.

Each module has the solution object(s) under the names the notebook's exercise cell uses (``most_forbidden``,
``my_vote``, ...; a list or text under an upper-case name, ``MY_ANSWER``, ``MY_INSTRUCTIONS``), and ``ANSWERS``:
the answer keys of the notebook's closing "Questions", keyed by question number (empty where a notebook asks
none). ``drywall_lab.course`` does not import this package: a notebook reaches it only when asked to.
"""
