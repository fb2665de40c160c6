"""drywall-lab."""
