r"""Earlier steps of a derivation (kinematics, energies, balances, stated results) compared with the truth of each step, and where an error enters."""
